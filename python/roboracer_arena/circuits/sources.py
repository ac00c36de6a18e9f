"""Reading the public circuit data in ``../shared/track-sources`` (see its SOURCES.md):
the TUM racetrack database CSVs (full-scale centreline with measured right/left widths)
and the bacinger GeoJSON circuits (WGS84 lon/lat centrelines, no widths).

The data is read in place, never copied into the project. :func:`circuit_inputs` lists
every circuit the library builds: all TUM circuits, plus every bacinger circuit whose
venue TUM does not cover with the same layout (same venue and lap length within 3 %).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import _core
from ..errors import MapFormatError, MapIOError
from ..foundation.fileio import read_json
from ..foundation.paths import sources_dir
from .projection import geodesic_length, project_local

TUM_DIR = "tumftm-racetrack-database"
BACINGER_DIR = "bacinger-f1-circuits"

#: Full-scale corridor width (m) used for every bacinger circuit: the data has no widths;
#: 12 m is the FIA Grade 1 minimum track width, so no circuit is drawn wider than it is.
BACINGER_WIDTH_M = 12.0

#: bacinger id -> the TUM track at the same venue (the layouts are compared by length).
SAME_VENUE = {
    "ae-2009": "YasMarina",
    "at-1969": "Spielberg",
    "au-1953": "Melbourne",
    "be-1925": "Spa",
    "bh-2002": "Sakhir",
    "br-1940": "SaoPaulo",
    "ca-1978": "Montreal",
    "cn-2004": "Shanghai",
    "de-1927": "Nuerburgring",
    "de-1932": "Hockenheim",
    "es-1991": "Catalunya",
    "gb-1948": "Silverstone",
    "hu-1986": "Budapest",
    "it-1922": "Monza",
    "jp-1962": "Suzuka",
    "mx-1962": "MexicoCity",
    "my-1999": "Sepang",
    "nl-1948": "Zandvoort",
    "ru-2014": "Sochi",
    "us-1909": "IMS",
    "us-2012": "Austin",
}
#: Layouts whose lap lengths differ by more than this are different circuits.
SAME_LAYOUT_TOL = 0.03
#: Same venue, different layout despite similar length: TUM "IMS" is the 2.5-mile oval
#: (constant 15.3 m width), bacinger us-1909 the Formula 1 road course.
DIFFERENT_LAYOUT = {"us-1909"}
#: Catalog ids for the bacinger circuits (the GeoJSON "Location" is often a town name).
BACINGER_IDS = {
    "ae-2009": "yas-marina-2009",
    "ar-1952": "buenos-aires",
    "az-2016": "baku",
    "br-1977": "jacarepagua",
    "es-2026": "madring",
    "fr-1960": "magny-cours",
    "fr-1969": "paul-ricard",
    "it-1914": "mugello",
    "it-1953": "imola",
    "mc-1929": "monaco",
    "pt-1972": "estoril",
    "pt-2008": "portimao",
    "qa-2004": "losail",
    "sa-2021": "jeddah",
    "sg-2008": "marina-bay",
    "tr-2005": "istanbul-park",
    "us-1909": "indianapolis-road-course",
    "us-1956": "watkins-glen",
    "us-2022": "miami",
    "us-2023": "las-vegas",
    "za-1961": "kyalami",
}


@dataclass
class CircuitInput:
    """One circuit at full scale: closed centreline (no repeated end point) in local
    metres, full corridor width per vertex, and its provenance."""

    id: str
    name: str
    source: str  # "tumftm" | "bacinger"
    path: Path
    xy: np.ndarray
    widths: np.ndarray
    width_note: str
    meta: dict = field(default_factory=dict)

    @property
    def length_m(self) -> float:
        """Full-scale lap length (m) of the closed centreline."""
        return _core.polyline_length(self.xy)


def slug(text: str) -> str:
    """``"SaoPaulo"`` -> ``"sao-paulo"``, ``"Spa Francorchamps"`` -> ``"spa-francorchamps"``."""
    import unicodedata

    t = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode()
    t = re.sub(r"(?<=[a-z])(?=[A-Z])", "-", t)
    return re.sub(r"[^a-z0-9]+", "-", t.lower()).strip("-")


def _drop_closing_duplicate(a: np.ndarray) -> np.ndarray:
    return a[:-1] if len(a) > 3 and np.allclose(a[0, :2], a[-1, :2]) else a


def read_tum_csv(path: str | Path) -> CircuitInput:
    """Read a TUM ``x_m, y_m, w_tr_right_m, w_tr_left_m`` CSV.

    The centreline is moved to the middle of the measured corridor, so a symmetric raster
    reproduces both edges: ``c + n (w_left − w_right) / 2`` with ``n`` the left normal.
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as e:
        raise MapIOError(f"{p}: cannot read circuit CSV: {e.strerror or e}") from e
    rows = []
    for lineno, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        parts = [v for v in re.split(r"[,;\s]+", s) if v]
        try:
            vals = [float(v) for v in parts]
        except ValueError:
            raise MapFormatError(f"{p}:{lineno}: expected numbers x, y, w_right, w_left, got {line!r}") from None
        if len(vals) != 4:
            raise MapFormatError(f"{p}:{lineno}: expected 4 columns (x, y, w_right, w_left), got {len(vals)}")
        rows.append(vals)
    a = _drop_closing_duplicate(np.asarray(rows, float).reshape(-1, 4))
    if len(a) < 4:
        raise MapFormatError(f"{p}: a closed centreline needs ≥ 4 points, got {len(a)}")
    if not np.isfinite(a).all() or (a[:, 2:] <= 0).any():
        raise MapFormatError(f"{p}: coordinates must be finite and widths > 0")
    xy, wr, wl = a[:, :2], a[:, 2], a[:, 3]
    tangent = np.roll(xy, -1, axis=0) - np.roll(xy, 1, axis=0)
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    normal_left = np.column_stack([-tangent[:, 1], tangent[:, 0]])
    mid = xy + normal_left * ((wl - wr) / 2)[:, None]
    return CircuitInput(
        id=slug(p.stem),
        name=re.sub(r"(?<=[a-z])(?=[A-Z])", " ", p.stem),
        source="tumftm",
        path=p,
        xy=mid,
        widths=wr + wl,
        width_note="measured (TUM w_tr_right + w_tr_left)",
    )


def read_geojson(path: str | Path, width_m: float = BACINGER_WIDTH_M) -> CircuitInput:
    """Read a GeoJSON LineString circuit (FeatureCollection, Feature or bare geometry),
    project it to local metres (transverse Mercator, WGS84) and give it a constant width."""
    p = Path(path)
    doc = read_json(p, "GeoJSON circuit", MapFormatError, max_bytes=256 * 2**20)
    feat = doc
    if isinstance(doc, dict) and doc.get("type") == "FeatureCollection":
        feats = doc.get("features") or []
        lines = [f for f in feats if (f.get("geometry") or {}).get("type") in ("LineString", "MultiLineString")]
        if not lines:
            raise MapFormatError(f"{p}: the FeatureCollection holds no LineString feature")
        feat = lines[0]
    geom = feat.get("geometry", feat) if isinstance(feat, dict) else None
    props = feat.get("properties") or {} if isinstance(feat, dict) else {}
    if not isinstance(geom, dict) or geom.get("type") not in ("LineString", "MultiLineString"):
        raise MapFormatError(f"{p}: expected a LineString geometry")
    coords = geom.get("coordinates")
    if geom["type"] == "MultiLineString":
        coords = max(coords or [[]], key=len)
    try:
        ll = np.asarray(coords, float)[:, :2]
    except (TypeError, ValueError, IndexError):
        raise MapFormatError(f"{p}: coordinates must be a list of [lon, lat] pairs") from None
    ll = _drop_closing_duplicate(ll)
    if len(ll) < 4 or not np.isfinite(ll).all() or (np.abs(ll[:, 1]) > 90).any():
        raise MapFormatError(f"{p}: a closed circuit needs ≥ 4 finite [lon, lat] points")
    cid = str(props.get("id") or p.stem)
    name = str(props.get("Name") or props.get("name") or cid)
    location = str(props.get("Location") or "")
    meta = {
        "bacinger_id": cid,
        "location": location,
        "stated_length_m": props.get("length"),
        "geodesic_length_m": round(geodesic_length(ll), 2),
    }
    return CircuitInput(
        id=BACINGER_IDS.get(cid) or slug(location or name),
        name=name,
        source="bacinger",
        path=p,
        xy=project_local(ll),
        widths=np.full(len(ll), float(width_m)),
        width_note=f"constant {width_m:g} m full scale (no widths in the data)",
        meta=meta,
    )


def circuit_inputs(sources: str | Path | None = None) -> tuple[list[CircuitInput], list[dict]]:
    """Every circuit to build, and the bacinger circuits skipped as covered by TUM (with why)."""
    root = sources_dir(sources, "building the circuit library")
    tum_files = sorted((root / TUM_DIR / "tracks").glob("*.csv"))
    geo_files = sorted((root / BACINGER_DIR / "circuits").glob("*.geojson"))
    if not tum_files and not geo_files:
        raise MapIOError(
            f"{root}: no circuit data found (expected {TUM_DIR}/tracks/*.csv, {BACINGER_DIR}/circuits/*.geojson)"
        )
    tum = {f.stem: read_tum_csv(f) for f in tum_files}
    out = list(tum.values())
    skipped = []
    ids = {c.id for c in out}
    for f in geo_files:
        c = read_geojson(f)
        twin = tum.get(SAME_VENUE.get(c.meta["bacinger_id"], ""))
        if twin is not None and c.meta["bacinger_id"] in DIFFERENT_LAYOUT:
            c.meta["differs_from"] = {"tum": twin.id, "reason": "different layout at the same venue"}
        elif twin is not None:
            rel = abs(c.length_m - twin.length_m) / twin.length_m
            if rel <= SAME_LAYOUT_TOL:
                skipped.append(
                    {
                        "bacinger_id": c.meta["bacinger_id"],
                        "name": c.name,
                        "covered_by": twin.id,
                        "length_difference": round(rel, 4),
                    }
                )
                continue
            c.meta["differs_from"] = {"tum": twin.id, "length_difference": round(rel, 4)}
        if c.id in ids:
            c.id = f"{c.id}-{c.meta['bacinger_id'].split('-')[1]}"
        ids.add(c.id)
        out.append(c)
    return out, skipped
