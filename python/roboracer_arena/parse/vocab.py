"""Word lists shared by the rules parser and the grounding guard, as regex fragments over
canonical tokens (see :mod:`.lexer`) and plain sets."""

from __future__ import annotations


def alt(*words: str) -> str:
    """``(?:w1|w2|...)`` with longer alternatives first."""
    return "(?:" + "|".join(sorted(words, key=len, reverse=True)) + ")"


#: A canonical number (see :func:`.lexer._fmt`): sign, decimals and exponent included.
NUM = r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?"
UNIT = alt("m", "cm", "mm", "km", "ft", "yd", "inch")

HALL_NOUNS = (
    "hall", "halls", "room", "rooms", "gym", "gymnasium", "space", "venue", "arena", "area",
    "warehouse", "garage", "lab", "laboratory", "floor", "building", "hangar", "court",
    "basement", "atrium", "footprint", "site", "shed", "studio", "auditorium", "workshop",
    "field", "plot", "box", "bounding", "envelope",
)  # fmt: skip
LAP_NOUNS = (
    "lap", "laps", "loop", "loops", "circuit", "circuits", "track", "tracks", "course",
    "courses", "racetrack", "racetracks", "centreline", "layout", "route", "ring", "oval",
    "raceway",
)  # fmt: skip
CORRIDOR_NOUNS = ("corridor", "corridors", "lane", "lanes", "passage", "road", "roadway", "lane")

HALL = alt(*HALL_NOUNS)
LAP = alt(*LAP_NOUNS)
CORR = alt(*CORRIDOR_NOUNS)

#: Connecting words allowed between a field noun and its number ("lap of about 45 m").
FILL_WORDS = (
    "of", "is", "be", "are", "should", "must", "shall", "will", "to", "about", "around",
    "roughly", "approximately", "approx", "exactly", "at", "least", "no", "not", "less",
    "smaller", "shorter", "than", "minimum", "min", "measuring", "measures", "measure",
    "that", "which", "just", "nearly", "almost", "precisely", "ideally", "set", "equal",
    "equals", "always", "needs", "need", "it", "its", ":", "=", "~", ">", "≥", "some",
    "total", "overall", "whose", "most", "more", "up", "under", "over", "max", "maximum", "below",
    "above", "exceeding", "longer", "wider", "bigger", "larger", "circa", "ca",
)  # fmt: skip
FILL = "(?:" + alt(*[w for w in FILL_WORDS if w]) + " ){0,5}"

FEATURE_NOUN = {"hairpin": "hairpins", "chicane": "chicanes", "sweeper": "sweepers"}
FEATURE_RE = r"(?:hairpin|chicane|sweeper)s?"
FEATURE_ADJ = alt(
    "tight", "tighter", "sharp", "sharper", "long", "short", "fast", "slow", "quick",
    "gentle", "wide", "big", "large", "small", "technical", "flowing", "high", "low",
    "speed", "consecutive", "successive", "separate", "more", "extra", "additional",
    "distinct", "medium", "slight", "open", "tricky", "hard", "easy", "left", "right",
    "hand", "handed", "fast", "nice", "decent", "proper", "full", "broad", "narrow",
    "gradual", "smooth", "quick",
)  # fmt: skip

#: Words that carry no TrackSpec content; never reported as unparsed.
FILLER = set(FILL_WORDS) | set(HALL_NOUNS) | set(LAP_NOUNS) | set(CORRIDOR_NOUNS) | {
    "i", "i'd", "i'm", "we", "we'd", "we're", "me", "us", "you", "my", "our", "please",
    "want", "wants", "wanted", "would", "like", "make", "generate", "create", "build",
    "design", "give", "get", "draw", "produce", "lay", "out", "could", "can", "may", "was",
    "in", "inside", "within", "into", "for", "on", "from", "and", "or", "plus", "as",
    "well", "also", "this", "these", "those", "there", "here", "so", "sports", "indoor",
    "indoors", "small", "large", "big", "tiny", "compact", "medium", "sized", "size",
    "modest", "roomy", "spacious", "fits", "fit", "fitting", "simple", "new", "roboracer",
    "f1tenth", "car", "cars", "direction", "driven", "driving", "drive", "run", "runs",
    "running", "going", "go", "goes", "raced", "thanks", "thank", "okay", "ok", "hi",
    "hello", "let's", "let", "one", "race", "racing", "map", "environment", "somewhere",
    "available", "only", "all", "both", "each", "every", "any", "it's", "i'll",
    "do", "does", "something", "arrange", "arranged", "placed", "put", "s",
    "sense", "used", "use", "using", "by", "a", "an", "the", "with", "has", "have", "having",
    "where", "whose", "what", "around", "dimensions", "dimension", "measurements", "turn", "turns", "corner", "corners", "bend", "bends", "curve", "curves", "call", "named",
}  # fmt: skip

#: Words that order features along the lap; "after"-type words reverse the order.
ORDER_FORWARD = {
    "then", "followed", "next", "afterwards", "afterward", "before", "finally", "subsequently",
    "later", "into", "second", "third", "fourth", "fifth", "last", "lastly", "thereafter",
    "leading", "ending", "ends", "precedes", "precede", "preceding",
}  # fmt: skip
ORDER_REVERSE = {"after", "following", "follows", "follow", "preceded"}
ORDER_START = {"first", "firstly", "start", "starting", "starts", "begin", "beginning", "begins", "opening", "opens"}
