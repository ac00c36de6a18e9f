"""File access at the edges: outputs checked up front and written atomically, inputs
read only when they are regular files of bounded size.

Outputs go to temporary files created exclusively (``mkstemp``: ``O_EXCL``, random short
names) beside their targets and are renamed into place only when every one of them is
complete, so a crash, a bad input or a planted symlink never leaves a half-written,
partial or redirected output behind. Every ``OSError`` becomes a one-line
:class:`~roboracer_arena.errors.MapIOError`.
"""

from __future__ import annotations

import errno
import fcntl
import json
import os
import re
import shutil
import signal
import stat
import tempfile
import weakref
from collections.abc import Callable, Container, Iterable, Iterator, Sequence
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import Any, TypeVar

from pydantic import BaseModel, ValidationError

from ..errors import InvalidArgumentError, MapFormatError, MapIOError
from .strict import validation_line

M = TypeVar("M", bound=BaseModel)

_UMASK = os.umask(0)  # read the process umask once (os.umask can only read by setting)
os.umask(_UMASK)

#: Largest text input (spec, config, centreline CSV) read, in bytes.
MAX_TEXT_BYTES = 16 << 20
#: Longest file name most file systems accept, in bytes.
MAX_NAME_BYTES = 255
#: Deepest nesting of arrays and objects a JSON input may have (ours need fewer than 8).
MAX_JSON_DEPTH = 64


_HELD_SIGNALS = {signal.SIGINT, signal.SIGTERM}


@contextmanager
def signals_held() -> Iterator[None]:
    """Hold SIGINT and SIGTERM back (in this thread) until the block is done, for steps
    that must not stop half-way (a swap of two folders, a message inside a file format):
    Python runs a signal's handler between any two bytecodes."""
    old = signal.pthread_sigmask(signal.SIG_BLOCK, _HELD_SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def _why(e: OSError) -> str:
    return e.strerror or str(e)


def _same_file(a: Path, b: Path) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:
        return a.resolve() == b.resolve()


def image_named_by(yaml_text: str) -> str | None:
    """The ``image:`` file name a map YAML's text gives (without parsing the YAML, so a
    caller can guard that file before the loader runs), or None."""
    m = re.search(r"^\s*image:\s*['\"]?([^'\"\n]+?)['\"]?\s*$", yaml_text, re.M)
    return m.group(1).strip() if m else None


def referenced_inputs(path: str | Path) -> list[Path]:
    """Files that the input ``path`` names and a command reads with it: the image of a
    ROS map YAML. A YAML that cannot be read is left for its loader to report."""
    path = Path(path)
    if path.suffix.lower() not in (".yaml", ".yml") or not path.is_file():
        return []

    try:
        image = image_named_by(read_text(path, "map YAML", 1 << 20))
    except (MapIOError, OSError):
        return []
    return [path.parent / image] if image else []


def _probe_writable(directory: Path, path: Path) -> None:
    # os.access says yes to root even on a read-only mount: create and remove a file instead.
    try:
        fd, probe = tempfile.mkstemp(prefix=".arena-probe-", dir=directory)
        os.close(fd)
        os.unlink(probe)
    except OSError as e:
        raise MapIOError(f"{path}: directory {directory} is not writable: {_why(e)}") from None


def check_output(path: str | Path, inputs: Iterable[str | Path | None] = (), *, directory: bool = False) -> Path:
    """The one output guard, called before any work: refuse an output path that cannot
    be written, i.e. a directory (a file for ``directory=True``), a name over 255 bytes,
    a parent that is a file or not a writable directory (probed by creating a file), or
    one of the command's ``inputs`` or a file an input names (:func:`referenced_inputs`),
    which it would destroy. Errors are one-line :class:`MapIOError` /
    :class:`InvalidArgumentError` (CLI exit 2)."""
    path = Path(path)
    if not path.name or len(os.fsencode(path.name)) > MAX_NAME_BYTES:
        raise MapIOError(f"{str(path)[:80]}…: file name must be 1 to {MAX_NAME_BYTES} bytes")
    if directory:
        if path.exists() and not path.is_dir():
            raise MapIOError(f"{path}: is not a directory; give a directory to write")
    elif path.is_dir():
        raise MapIOError(f"{path}: is a directory; give a file name to write")
    given = [Path(src) for src in inputs if src is not None]
    for src in [*given, *(r for g in given for r in referenced_inputs(g))]:
        if not src.exists():
            continue
        if _same_file(path, src):
            raise InvalidArgumentError(f"{path}: the output would overwrite the input {src}")
    anc = path.parent
    while not anc.exists() and anc != anc.parent:
        anc = anc.parent
    if not anc.is_dir():
        raise MapIOError(f"{path}: {anc} is not a directory")
    if not os.access(anc, os.W_OK | os.X_OK):
        raise MapIOError(f"{path}: directory {anc} is not writable")
    _probe_writable(anc, path)
    return path


class StagedFile:
    """An output written in place over time (a recording): checked with
    :func:`check_output` at creation, written to a hidden temporary file beside the target,
    renamed into place with the umask's permissions by :meth:`commit`, or deleted by
    :meth:`discard`. A staged file never committed is deleted when the object is collected
    or the interpreter exits, so no exit path but SIGKILL leaves a temporary behind."""

    def __init__(self, path: str | Path, inputs: Iterable[str | Path | None] = ()) -> None:
        self.path = check_output(path, inputs)
        try:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self.tmp = _temp_beside(self.path)
        except OSError as e:
            raise MapIOError(f"{self.path}: cannot write: {_why(e)}") from None
        self._finalizer = weakref.finalize(self, _unlink_quietly, self.tmp)

    def commit(self) -> Path:
        """Give the finished temporary file the usual permissions and move it into place."""
        try:
            os.chmod(self.tmp, 0o666 & ~_UMASK)  # mkstemp makes 0600
            os.replace(self.tmp, self.path)
        except OSError as e:
            self.discard()
            raise MapIOError(f"{self.path}: cannot write: {_why(e)}") from None
        self._finalizer.detach()
        return self.path

    def discard(self) -> None:
        """Delete the temporary file (idempotent)."""
        self._finalizer()


def _unlink_quietly(p: Path) -> None:
    with suppress(OSError):
        p.unlink(missing_ok=True)


def _temp_beside(path: Path) -> Path:
    # Short random name (the target's own name may already be 255 bytes); keep a short
    # suffix, since some writers (usd-core) choose the encoding by extension.
    suffix = path.suffix if len(path.suffix) <= 16 else ""
    fd, tmp = tempfile.mkstemp(prefix=".arena-", suffix=suffix, dir=path.parent)
    os.close(fd)
    return Path(tmp)


@contextmanager
def atomic_paths(paths: Sequence[str | Path]) -> Iterator[list[Path]]:
    """Yield one temporary path per target (same order); when the block succeeds rename
    them all into place, else delete them. Files and directories that this call created
    are removed again if any rename fails, so the set appears completely or not at all."""
    targets = [check_output(p) for p in paths]
    made_dirs: list[Path] = []
    temps: list[Path] = []
    committed: list[Path] = []
    ok = False
    try:
        for t in targets:
            missing = [d for d in [t.parent, *t.parent.parents] if not d.exists()]
            t.parent.mkdir(parents=True, exist_ok=True)
            made_dirs.extend(reversed(missing))
            temps.append(_temp_beside(t))
        yield list(temps)
        for tmp in temps:
            os.chmod(tmp, 0o666 & ~_UMASK)  # mkstemp makes 0600; give the usual permissions
        for tmp, t in zip(temps, targets):
            existed = t.exists()
            os.replace(tmp, t)
            if not existed:
                committed.append(t)
        ok = True
    except OSError as e:
        where = getattr(e, "filename", None) or (targets[0] if targets else "")
        named = {str(t): str(target) for t, target in zip(temps, targets)}  # the target, not its temporary
        raise write_failure(named.get(str(where), where), e) from e
    finally:
        leftovers = temps if ok else [*temps, *committed]
        for p in leftovers:
            with suppress(OSError):
                Path(p).unlink(missing_ok=True)
        if not ok:
            for d in reversed(made_dirs):
                with suppress(OSError):
                    d.rmdir()


@contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success rename it onto ``path``,
    on any exception delete it. For writers that insist on a file name (usd-core)."""
    with atomic_paths([path]) as (tmp,):
        yield tmp


def atomic_write_bytes(path: str | Path, data: bytes) -> None:
    with atomic_path(path) as tmp:
        tmp.write_bytes(data)


def atomic_write_text(path: str | Path, text: str) -> None:
    atomic_write_bytes(path, text.encode("utf-8"))


def require_regular(path: str | Path, what: str) -> os.stat_result:
    """The ``stat`` of ``path`` if it is a regular file (symlinks followed); else a
    one-line :class:`MapIOError` saying what it is instead: missing, a directory, a FIFO,
    a device or a symlink loop. Nothing is opened (a FIFO would block)."""
    path = Path(path)
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise MapIOError(f"{path}: cannot read {what}: does not exist") from None
    except OSError as e:
        why = "is a symlink loop" if e.errno == 40 or "symbolic links" in _why(e) else _why(e)
        raise MapIOError(f"{path}: cannot read {what}: {why}") from None
    if not stat.S_ISREG(st.st_mode):
        kind = (
            "a directory"
            if stat.S_ISDIR(st.st_mode)
            else "a FIFO (named pipe)"
            if stat.S_ISFIFO(st.st_mode)
            else "a device"
            if stat.S_ISCHR(st.st_mode) or stat.S_ISBLK(st.st_mode)
            else "a socket or other special file"
        )
        raise MapIOError(f"{path}: cannot read {what}: it is {kind}, not a regular file")
    return st


def read_regular_bytes(path: str | Path, what: str, max_bytes: int = MAX_TEXT_BYTES) -> bytes:
    """The bytes of the regular file ``path`` (a ``what``, for messages), at most
    ``max_bytes``; anything but a regular file is refused by :func:`require_regular`
    before it is opened (a FIFO would block, ``/dev/zero`` never ends)."""
    path = Path(path)
    st = require_regular(path, what)
    if st.st_size > max_bytes:
        raise MapIOError(f"{path}: {what} is {st.st_size} bytes, more than the {max_bytes} allowed")
    try:
        with open(path, "rb") as f:
            data = f.read(max_bytes + 1)
    except OSError as e:
        raise MapIOError(f"{path}: cannot read {what}: {_why(e)}") from None
    if len(data) > max_bytes:
        raise MapIOError(f"{path}: {what} is more than the {max_bytes} bytes allowed")
    return data


def read_text(path: str | Path, what: str, max_bytes: int = MAX_TEXT_BYTES) -> str:
    """:func:`read_regular_bytes` decoded as UTF-8 (a BOM is allowed); UTF-16 or other
    encodings are refused with a one-line error naming the file."""
    data = read_regular_bytes(path, what, max_bytes)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        hint = " (it looks like UTF-16; save it as UTF-8)" if data[:2] in (b"\xff\xfe", b"\xfe\xff") else ""
        raise MapIOError(f"{path}: {what} is not UTF-8 text (byte {e.start}){hint}") from None


def parse_json(text: str, where: str | Path, what: str, error: type[Exception] = MapFormatError) -> Any:
    """The one JSON parser of the package's input files: malformed JSON, nesting deeper
    than :data:`MAX_JSON_DEPTH` and values Python refuses (an integer of more than 4300
    digits) raise ``error`` with one line naming ``where`` and ``what`` it is."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise error(f"{where}: {what} is not valid JSON (line {e.lineno}, column {e.colno}): {e.msg}") from None
    except RecursionError:
        raise error(f"{where}: {what} is JSON nested too deeply (more than {MAX_JSON_DEPTH} levels)") from None
    except ValueError as e:  # int_max_str_digits: a 5000-digit integer
        raise error(f"{where}: {what} holds a number JSON cannot be read as: {str(e).split(';')[0]}") from None
    if json_depth(data) > MAX_JSON_DEPTH:
        raise error(f"{where}: {what} is JSON nested too deeply (more than {MAX_JSON_DEPTH} levels)")
    return data


def json_depth(data: Any) -> int:
    """Nesting depth of a parsed JSON value (a scalar is 0), counted without recursion."""
    deepest, todo = 0, [(data, 0)]
    while todo:
        item, depth = todo.pop()
        if isinstance(item, dict):
            item = list(item.values())
        if isinstance(item, list):
            deepest = max(deepest, depth + 1)
            if deepest > MAX_JSON_DEPTH:
                return deepest
            todo.extend((x, depth + 1) for x in item if isinstance(x, (list, dict)))
    return deepest


def read_json(
    path: str | Path, what: str, error: type[Exception] = MapFormatError, max_bytes: int = MAX_TEXT_BYTES
) -> Any:
    """A JSON document from :func:`read_text` (regular file, size cap, UTF-8) parsed by
    :func:`parse_json`."""
    return parse_json(read_text(path, what, max_bytes), path, what, error)


def validate_model(
    data: Any, model: type[M], where: str | Path, what: str, error: type[Exception] = MapFormatError
) -> M:
    """``data`` (parsed JSON) as the pydantic ``model``; a value of the wrong shape or type
    raises ``error`` with one line naming ``where``, ``what`` and each field at fault."""
    try:
        return model.model_validate(data)
    except ValidationError as e:
        raise error(f"{where}: {what}: {validation_line(e)}") from None
    except (RecursionError, OverflowError, ValueError, TypeError) as e:  # a validator meeting a hostile value
        raise error(f"{where}: {what}: {type(e).__name__}: {str(e)[:200]}") from None


def parse_json_model(
    text: str, model: type[M], where: str | Path, what: str, error: type[Exception] = MapFormatError
) -> M:
    """:func:`parse_json`, then :func:`validate_model`: the one reader of a typed JSON text."""
    return validate_model(parse_json(text, where, what, error), model, where, what, error)


def read_json_model(
    path: str | Path,
    model: type[M],
    what: str,
    error: type[Exception] = MapFormatError,
    max_bytes: int = MAX_TEXT_BYTES,
) -> M:
    """The one reader of a typed JSON file: regular file, at most ``max_bytes``, UTF-8,
    valid JSON nested at most :data:`MAX_JSON_DEPTH` deep, and of ``model``'s shape; else
    ``error`` with one line naming the file and the field (CLI exit 2)."""
    return validate_model(read_json(path, what, error, max_bytes), model, path, what, error)


@contextmanager
def file_lock(path: str | Path) -> Iterator[None]:
    """Hold an exclusive lock (``fcntl.flock``) on the hidden lock file ``.NAME.lock``
    beside ``path`` for the block: writers that read, change and write back ``path`` take
    it around the whole step, so none works on a copy another has since replaced. The lock
    file exists only while held: the holder removes it before releasing, and a waiter that
    then wakes on the removed file (its inode no longer the path's) takes the lock again on
    a fresh one, so two holders never overlap and no lock file is left behind. The lock is
    also released when the process dies."""
    p = Path(path)
    lock = p.with_name(f".{p.name}.lock")
    while True:
        try:
            fd = os.open(lock, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o666 & ~_UMASK)
        except OSError as e:
            raise MapIOError(f"{p}: cannot create its lock file {lock.name}: {_why(e)}") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX)
            try:
                current = os.stat(lock).st_ino
            except FileNotFoundError:
                current = None
        except BaseException:
            os.close(fd)
            raise
        if current == os.fstat(fd).st_ino:
            break
        os.close(fd)  # woke on a lock file its holder removed: take the lock on the new one
    try:
        yield
    finally:
        with suppress(OSError):
            os.unlink(lock)  # (while still held: see above)
        os.close(fd)  # releases the lock


def write_failure(target: str | Path, e: BaseException) -> MapIOError:
    """The one-line error for a write of ``target`` that failed with ``e`` (an ``OSError``
    or a writer's own exception, e.g. usd-core's ``Tf.ErrorException``): a full disk, a
    quota or a file-size limit says so and names the file the command was writing."""
    code = getattr(e, "errno", None)
    text = str(e).strip().splitlines()[-1] if str(e).strip() else type(e).__name__
    if code == errno.ENOSPC or "No space left" in str(e):
        why = "no space left on the device (the disk is full)"
    elif code == errno.EDQUOT or "quota" in str(e).lower():
        why = "disk quota exceeded"
    elif code == errno.EFBIG or "File too large" in str(e):
        why = "file too large (a file-size limit)"
    elif isinstance(e, OSError):
        why = _why(e)
    else:
        why = text[:200]
    return MapIOError(f"{target}: cannot write: {why}")


@contextmanager
def atomic_dir(path: str | Path, also: Callable[[], object] | None = None) -> Iterator[Path]:
    """Yield a fresh temporary sibling directory of ``path``; when the block succeeds it
    replaces ``path`` by rename (a previous ``path`` is moved aside first and deleted after),
    so readers see the old folder or the new one, never a mix. On any error the temporary
    folder is removed and ``path`` is left as it was. ``also`` (e.g. the
    :meth:`StagedFile.commit` of a file describing the folder) runs in the same step as the
    swap, signals held: if it fails the earlier folder is put back, so both land or
    neither."""
    path = Path(path)
    parent = path.absolute().parent
    stage = _Stage()
    with signals_held():  # the stage and its clean-up come into being together
        try:
            parent.mkdir(parents=True, exist_ok=True)
            tmp = Path(tempfile.mkdtemp(prefix=f".{path.name}.", suffix=".tmp", dir=parent))
            os.chmod(tmp, 0o777 & ~_UMASK)  # mkdtemp makes 0700; the folder is a normal output
        except OSError as e:
            raise MapIOError(f"{path}: cannot create the output directory: {_why(e)}") from None
        # However this block is left (an interrupt between any two bytecodes included),
        # the stage goes when ``stage`` does; after the swap its name no longer exists.
        weakref.finalize(stage, shutil.rmtree, tmp, True)
    old: Path | None = None
    try:
        yield tmp
        with signals_held():  # the renames (and ``also``) happen all or none
            if path.exists():
                old = Path(tempfile.mkdtemp(prefix=f".{path.name}.", suffix=".old", dir=parent))
                os.replace(path, old / "previous")
            os.replace(tmp, path)
            if also is not None:
                try:
                    also()
                except BaseException:
                    os.replace(path, tmp)  # undo the swap; the handler below restores the old one
                    raise
            if old is not None:  # in the same held step: no moment leaves it behind
                shutil.rmtree(old, ignore_errors=True)
    except BaseException:
        with signals_held():
            if old is not None:
                if not path.exists():
                    os.replace(old / "previous", path)  # put the earlier folder back
                shutil.rmtree(old, ignore_errors=True)
            shutil.rmtree(tmp, ignore_errors=True)
        raise


@contextmanager
def atomic_update_dir(
    path: str | Path, rewritten: Container[str], also: Callable[[], object] | None = None
) -> Iterator[Path]:
    """:func:`atomic_dir` for a job that rewrites some entries of the folder ``path``: the
    stage starts with hard links (:func:`link_tree`) to everything ``path`` holds whose
    name is not in ``rewritten``, so the swap keeps the rest and a rewritten entry is
    whatever the job made of it (nothing, if it made none)."""
    old = Path(path)
    with atomic_dir(old, also=also) as stage:
        if old.is_dir():
            for item in old.iterdir():
                if item.name not in rewritten:
                    link_tree(item, stage / item.name)
        yield stage


class _Stage:
    """A token whose lifetime is one :func:`atomic_dir` block (its stage's clean-up hangs on it)."""


def link_tree(src: Path, dst: Path) -> None:
    """Reproduce ``src`` (a file, a symlink or a folder tree) at ``dst`` by hard links,
    copying where a link is impossible: how a staged folder carries over, at no cost,
    what the job does not rewrite."""

    def link(a: str, b: str) -> None:
        try:
            os.link(a, b)
        except OSError:
            shutil.copy2(a, b)

    if src.is_dir() and not src.is_symlink():
        shutil.copytree(src, dst, symlinks=True, copy_function=link)
    elif src.is_symlink():
        os.symlink(os.readlink(src), dst)
    else:
        link(str(src), str(dst))


def atomic_write_dir(path: str | Path, files: dict[str, bytes]) -> None:
    """Write ``files`` (name -> bytes) as the directory ``path``, all or nothing
    (:func:`atomic_dir`)."""
    with atomic_dir(path) as tmp:
        for name, data in files.items():
            (tmp / name).write_bytes(data)
            os.chmod(tmp / name, 0o666 & ~_UMASK)
