"""The policy file: round trip, refusal of corrupt or mismatched files (typed error, exit 2
from the CLI with one line), and which beams of a scan a policy reads."""

from __future__ import annotations

import io
import json
import zipfile

import numpy as np
import pytest

from roboracer_arena.cli import main
from roboracer_arena.envs.env_config import EnvConfig
from roboracer_arena.errors import PolicyFileError
from roboracer_arena.learn.policy import PolicySpec, init_params
from roboracer_arena.learn.policy_file import Policy, load_policy, policy_from_bytes
from roboracer_arena.learn.runner import check_env, scan_indices


def _spec(**kw) -> PolicySpec:
    base = dict(
        num_beams=55,
        fov=4.71238898,
        horizon=10.0,
        max_steer=0.524,
        max_speed=7.0,
        min_speed=0.5,
        base="pure_pursuit",
        control_rate_hz=20.0,
        hidden=8,
    )
    base.update(kw)
    return PolicySpec(**base)


def _policy(**kw) -> Policy:
    spec = _spec(**kw)
    theta = init_params(spec, np.random.default_rng(0))
    return Policy(spec, theta, {"control_rate_hz": 20.0}, {"recipe": {"seed": 0}}, {"m": theta * 0, "v": theta * 0})


def test_round_trip_keeps_everything(tmp_path):
    p = _policy()
    path = p.save(tmp_path / "p.npz")
    q = load_policy(path)
    assert q.spec == p.spec and np.array_equal(q.theta, p.theta)
    assert q.env == p.env and q.training == p.training
    assert q.optimiser is not None and np.array_equal(q.optimiser["m"], p.optimiser["m"])
    x = np.random.default_rng(1).uniform(0, 10, (3, 55))
    base = np.array([[0.1, 2.0], [0.0, 3.0], [-0.2, 1.0]])
    assert np.array_equal(q.act(x, [1, 2, 3], [0, 0.1, 0], base), p.act(x, [1, 2, 3], [0, 0.1, 0], base))


def test_zero_network_is_its_base():
    p = _policy()
    p.theta[:] = 0.0
    base = np.array([[0.2, 3.0], [-0.3, 1.5]])
    out = p.act(np.full((2, 55), 5.0), [1.0, 2.0], [0.0, 0.0], base)
    assert np.allclose(out, base)


def _rewrite(data: bytes, edit) -> bytes:
    """The archive with ``edit(arrays)`` applied (arrays: name -> ndarray)."""
    with np.load(io.BytesIO(data)) as z:
        arrays = {k: z[k] for k in z.files}
    edit(arrays)
    buf = io.BytesIO()
    np.savez(buf, **arrays)
    return buf.getvalue()


def _header_edit(change):
    def edit(arrays):
        h = json.loads(arrays["header"].tobytes())
        change(h)
        arrays["header"] = np.frombuffer(json.dumps(h).encode(), np.uint8)

    return edit


CORRUPT = {
    "garbage": lambda d: b"not a policy",
    "truncated": lambda d: d[: len(d) // 2],
    "empty": lambda d: b"",
    "no header": lambda d: _rewrite(d, lambda a: a.pop("header")),
    "header not json": lambda d: _rewrite(d, lambda a: a.__setitem__("header", np.frombuffer(b"{nope", np.uint8))),
    "header a list": lambda d: _rewrite(d, lambda a: a.__setitem__("header", np.frombuffer(b"[1]", np.uint8))),
    "wrong format": lambda d: _rewrite(d, _header_edit(lambda h: h.__setitem__("format", "other"))),
    "future version": lambda d: _rewrite(d, _header_edit(lambda h: h.__setitem__("version", 99))),
    "string beams": lambda d: _rewrite(d, _header_edit(lambda h: h["spec"].__setitem__("num_beams", "55"))),
    "negative horizon": lambda d: _rewrite(d, _header_edit(lambda h: h["spec"].__setitem__("horizon", -1))),
    "beams not matching layer": lambda d: _rewrite(d, _header_edit(lambda h: h["spec"].__setitem__("num_beams", 54))),
    "missing layer": lambda d: _rewrite(d, lambda a: a.pop("w1")),
    "nan weights": lambda d: _rewrite(d, lambda a: a["w0"].__setitem__((0, 0), np.nan)),
    "int layer": lambda d: _rewrite(d, lambda a: a.__setitem__("b0", a["b0"].astype(np.int64))),
    "object array": lambda d: _rewrite(d, lambda a: a.__setitem__("b1", np.array([object(), object()]))),
    "extra array": lambda d: _rewrite(d, lambda a: a.__setitem__("surprise", np.zeros(3))),
    "bad optimiser": lambda d: _rewrite(d, lambda a: a.__setitem__("adam_m", np.zeros(3))),
}


@pytest.mark.parametrize("case", sorted(CORRUPT))
def test_corrupt_files_are_refused_with_a_typed_error(case):
    good = _policy().to_bytes()
    try:
        bad = CORRUPT[case](good)
    except ValueError:  # numpy refuses to even write an object array without pickles
        pytest.skip("numpy cannot write this case")
    with pytest.raises(PolicyFileError, match="policy"):
        policy_from_bytes(bad, "bad.npz")


def test_random_byte_flips_never_escape_the_typed_error():
    good = _policy().to_bytes()
    rng = np.random.default_rng(7)
    for _ in range(300):
        b = bytearray(good)
        for i in rng.integers(0, len(b), rng.integers(1, 8)):
            b[i] = rng.integers(0, 256)
        try:
            policy_from_bytes(bytes(b), "flipped.npz")
        except PolicyFileError:
            pass


def test_a_directory_and_a_missing_file_are_refused(tmp_path):
    for p in (tmp_path, tmp_path / "missing.npz"):
        with pytest.raises(PolicyFileError):
            load_policy(p)


def test_scan_indices_read_every_twentieth_of_1081_beams():
    spec = _spec()
    assert np.array_equal(scan_indices(spec, 1081, spec.fov), np.arange(0, 1081, 20))
    assert np.array_equal(scan_indices(spec, 55, spec.fov), np.arange(55))
    with pytest.raises(PolicyFileError, match="beams"):
        scan_indices(spec, 1080, spec.fov)
    with pytest.raises(PolicyFileError, match="fov"):
        scan_indices(spec, 1081, 3.14)


def test_env_that_does_not_fit_is_refused():
    spec = _spec()
    check_env(spec, EnvConfig.build({"sim": {"lidar": {"num_beams": 55}}}))
    with pytest.raises(PolicyFileError, match="Hz"):
        check_env(spec, EnvConfig.build({"sim": {"lidar": {"num_beams": 55}}, "control_rate_hz": 40}))
    with pytest.raises(PolicyFileError, match="beams"):
        check_env(spec, EnvConfig.build({"sim": {"lidar": {"num_beams": 60}}}))


def test_drive_refuses_a_corrupt_or_mismatched_file_with_exit_2(tmp_path, capsys):
    bad = tmp_path / "bad.npz"
    bad.write_bytes(b"PK\x03\x04 truncated")
    assert main(["drive", "gen-l040-w12-h2c1s1-clo-s0", "--policy", str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bad.npz" in err[0]
    odd = _policy(control_rate_hz=20.0)
    odd = Policy(odd.spec, odd.theta, {"control_rate_hz": 40.0}, {})  # header env disagrees with the spec
    path = odd.save(tmp_path / "odd.npz")
    assert main(["drive", "gen-l040-w12-h2c1s1-clo-s0", "--policy", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "Hz" in err[0]


def test_truncated_zip_member_is_refused():
    good = _policy().to_bytes()
    buf = io.BytesIO(good)
    with zipfile.ZipFile(buf) as z:
        names = z.namelist()
    assert "header.npy" in names
    with pytest.raises(PolicyFileError):
        policy_from_bytes(good[:-40], "cut.npz")
