"""A tiny HTTP server on 127.0.0.1 that speaks the part of Ollama's REST protocol the
official client uses here (``POST /api/chat`` with ``stream: false``, ``GET /api/tags``)
and answers with recorded model outputs. The tests drive the real ``ollama`` client
against it, so the client's own error behaviour (ConnectionError, ResponseError, raw
httpx timeouts) is what the backend sees."""

from __future__ import annotations

import json
import threading
import time
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any


@dataclass
class Reply:
    """What the server does for the next chat call."""

    content: str | None = None  # the model's message content
    status: int = 200
    body: str | None = None  # raw HTTP body (overrides content)
    delay_s: float = 0.0


@dataclass
class FakeOllama:
    reply: Reply = field(default_factory=Reply)
    models: list[str] = field(default_factory=lambda: ["gemma4:31b"])
    requests: list[dict[str, Any]] = field(default_factory=list)
    url: str = ""

    def chat_body(self, model: str) -> tuple[int, str]:
        r = self.reply
        if r.delay_s:
            time.sleep(r.delay_s)
        if r.body is not None:
            return r.status, r.body
        if model not in self.models:
            return 404, json.dumps({"error": f"model '{model}' not found"})
        msg = {
            "model": model,
            "created_at": "2026-01-01T00:00:00Z",
            "message": {"role": "assistant", "content": r.content or ""},
            "done": True,
            "done_reason": "stop",
            "total_duration": 1,
            "eval_count": 1,
        }
        return r.status, json.dumps(msg)


def start(fake: FakeOllama) -> tuple[ThreadingHTTPServer, threading.Thread]:
    class Handler(BaseHTTPRequestHandler):
        def _send(self, status: int, body: str) -> None:
            data = body.encode()
            self.send_response(status)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            try:
                self.wfile.write(data)
            except (BrokenPipeError, ConnectionResetError):
                pass  # the client gave up (timeout test)

        def do_GET(self) -> None:
            if self.path == "/api/tags":
                self._send(200, json.dumps({"models": [{"name": m, "model": m} for m in fake.models]}))
            else:
                self._send(404, json.dumps({"error": "not found"}))

        def do_POST(self) -> None:
            length = int(self.headers.get("Content-Length", 0))
            req = json.loads(self.rfile.read(length) or b"{}")
            fake.requests.append({"path": self.path, **req})
            if self.path != "/api/chat":
                self._send(404, json.dumps({"error": "not found"}))
                return
            self._send(*fake.chat_body(req.get("model", "")))

        def log_message(self, *args: Any) -> None:
            pass

    server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    server.daemon_threads = True
    fake.url = f"http://127.0.0.1:{server.server_address[1]}"
    thread = threading.Thread(target=server.serve_forever, kwargs={"poll_interval": 0.02}, daemon=True)
    thread.start()
    return server, thread
