"""Property test: requests composed from random phrase templates, in random order, parse
to exactly the stated fields (and nothing else), and the guard accepts them."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from roboracer_arena.parse import ground, parse_request
from roboracer_arena.parse.result import DEFAULTS

WORDS = {1: "one", 2: "two", 3: "three", 4: "four", 5: "five", 12: "twelve", 15: "fifteen", 20: "twenty",
         25: "twenty-five", 40: "forty", 45: "forty-five", 60: "sixty"}  # fmt: skip


def num(n: int, words: bool) -> str:
    return WORDS.get(n, str(n)) if words else str(n)


LAP = ["a {n} m lap", "a lap of {n} metres", "{n} metres long", "lap length {n} m", "a {n}-metre loop"]
HALL = ["in a {x} by {y} hall", "a {x}x{y} m room", "a hall {x} m long and {y} m wide", "a {x} × {y} m gym"]
WIDTH = ["a {w} m wide corridor", "corridor width of {w} m", "corridors {w} m wide", "{cm} cm lanes"]
DIRECTION = [("clockwise", "clockwise"), ("anticlockwise", "counterclockwise"), ("CCW", "counterclockwise"),
             ("driven counter-clockwise", "counterclockwise"), ("CW", "clockwise")]  # fmt: skip
RADIUS = ["a minimum radius of {r} m", "no turn tighter than {r} m", "a {r} m minimum radius"]
STRAIGHT = ["a longest straight of {s} m", "an {s} m straight", "a straight of at least {s} m"]
NAME = ['called "{nm}"', "named {nm}"]


@st.composite
def requests(draw):
    parts, want = [], {}
    words = draw(st.booleans())
    if draw(st.booleans()):
        n = draw(st.sampled_from([25, 40, 45, 60, 38, 52]))
        parts.append(draw(st.sampled_from(LAP)).format(n=num(n, words)))
        want["lap_length_m"] = float(n)
    if draw(st.booleans()):
        x, y = draw(st.sampled_from([(20, 15), (15, 12), (25, 18), (30, 20)]))
        parts.append(draw(st.sampled_from(HALL)).format(x=x, y=y))
        want["hall_x_m"], want["hall_y_m"] = float(x), float(y)
    if draw(st.booleans()):
        w = draw(st.sampled_from([1.2, 1.8, 2.0]))
        parts.append(draw(st.sampled_from(WIDTH)).format(w=w, cm=int(round(w * 100))))
        want["corridor_width_m"] = w
    if draw(st.booleans()):
        text, sense = draw(st.sampled_from(DIRECTION))
        parts.append(text)
        want["direction"] = sense
    if draw(st.booleans()):
        r = draw(st.sampled_from([1.5, 2.0, 2.5]))
        parts.append(draw(st.sampled_from(RADIUS)).format(r=r))
        want["min_radius_m"] = r
    if draw(st.booleans()):
        s = draw(st.sampled_from([8, 10]))
        parts.append(draw(st.sampled_from(STRAIGHT)).format(s=s).replace("an 10", "a 10"))
        want["longest_straight_m"] = float(s)
    feats = draw(st.lists(st.sampled_from(["hairpin", "chicane", "sweeper"]), unique=True, max_size=3))
    counts = {f: draw(st.integers(0, 3)) for f in feats}

    def say(f: str, n: int) -> str:
        return f"no {f}s" if n == 0 else (f"a {f}" if n == 1 else f"{num(n, words)} {f}s")

    positive = [f for f in feats if counts[f] > 0]
    ordered = len(positive) >= 2 and draw(st.booleans())
    if ordered:
        link = draw(st.sampled_from([" then ", ", followed by ", ", and then "]))
        parts.append(link.join(say(f, counts[f]) for f in positive))
        want["feature_order"] = [f for f in positive for _ in range(counts[f])]
    for f, n in counts.items():
        if not (ordered and n > 0):
            parts.append(say(f, n))
        want[f + "s"] = n
    if draw(st.booleans()):
        nm = draw(st.sampled_from(["Kestrel", "Blue Line", "Loop-9"]))
        parts.append(draw(st.sampled_from(NAME)).format(nm=nm))
        want["name"] = nm
    order = draw(st.permutations(range(len(parts))))
    sep = draw(st.sampled_from([", ", "; ", " and ", ". "]))
    return sep.join(parts[i] for i in order) or "a track", want


@settings(max_examples=300, deadline=None)
@given(requests())
def test_composed_requests_parse_exactly(req):
    text, want = req
    r = parse_request(text)
    got = r.spec.model_dump()
    expected = {**DEFAULTS, **want}
    assert {k: got[k] for k in got} == expected, text
    assert set(r.stated) == set(want), text
    assert r.unparsed == (), (text, r.unparsed)
    assert ground(text, r.spec, rules_reading=False).invented == {}
