"""Tracing one-degree-of-freedom chains (thesis ch. 6, issue 19): the double butterfly's
published starting configurations, its traced configuration space checked against
independent slices, and `baranov trace`."""

import math
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from baranov.cli.main import main
from baranov.motion import configurations_at, one_dof_system, sign_index, trace
from baranov.motion.continuation import distance_to_polyline
from baranov.scene import load_scene, scene_from_dict

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
#: The thesis's η: A2,4,10, A1,3,6, A1,6,5, A4,9,7, most significant first (§6.3).
ETA = [("P2", "P4", "P10"), ("P1", "P3", "P6"), ("P1", "P6", "P5"), ("P4", "P9", "P7")]


def _scaled(point, scale: np.ndarray) -> np.ndarray:
    return np.array(list(point.parameters.values())) / scale


def _on_piece(here: np.ndarray, piece, scale: np.ndarray, resolution: float) -> bool:
    """Whether ``here`` (parameters over their bounds) lies within ``resolution`` of the
    piece's polyline in the plane of the plan's parameters."""
    points = np.array([_scaled(p, scale) for p in piece.points])
    return distance_to_polyline(here, points, piece.closed) < resolution


@pytest.fixture(scope="module")
def butterfly():
    scene = load_scene(EXAMPLES / "double-butterfly.json")
    system = one_dof_system(scene, [("P2", "P4"), ("P1", "P6")])
    return system, trace(system)


def test_published_starting_configurations(butterfly):
    """Thesis §6.3: (s2,4, s1,6, η) = (74, 188.68, 8), (74, 122, 14), (74, 98.92, 0) lie on
    the configuration space, s2,4 within [62 − 4√130, 62 + 4√130]. Computed: s1,6 =
    188.6855 (the thesis prints 188.68; rounded, 188.69), 122.0000 and 98.9158, each with
    the published η; ten configurations in all at s2,4 = 74."""
    system, _ = butterfly
    assert system.upper[0] == pytest.approx(62 + 4 * math.sqrt(130), rel=1e-15)
    at_74 = {(round(p.parameters["s1,6"], 4), sign_index(p, ETA)) for p in configurations_at(system, 74.0)}
    assert {(188.6855, 8), (122.0, 14), (98.9158, 0)} <= at_74 and len(at_74) == 10


def test_traced_pieces_verify_and_do_not_jump(butterfly):
    """Every traced point satisfies every link constraint (relative residual < 1e-9); no
    joint moves more than 4 % of the linkage's size between neighbours; the three
    published starting configurations lie on pieces of their η."""
    system, traced = butterfly
    assert traced.pieces and not traced.jumps
    assert max(point.max_residual for piece in traced.pieces for point in piece.points) < 1e-9
    scale = np.array(system.upper)
    for s16, eta in [(188.6855, 8), (122.0, 14), (98.9158, 0)]:
        start = next(p for p in configurations_at(system, 74.0) if abs(p.parameters["s1,6"] - s16) < 1e-3)
        assert any(_on_piece(_scaled(start, scale), piece, scale, 1 / 200)
                   and sign_index(piece.middle, ETA) == eta
                   for piece in traced.pieces)


#: Thesis Table 6.1: the sign combinations of A2,4,10, A1,3,6, A1,6,5, A4,9,7 coloured in
#: Figs. 6.6–6.7 (−−−−, −−−+, −+−−, −+−+, −+++, +−−−, +−−+, ++−−, ++−+, +++−, ++++) as η.
TABLE_6_1 = {0b0000, 0b0001, 0b0100, 0b0101, 0b0111, 0b1000, 0b1001, 0b1100, 0b1101, 0b1110, 0b1111}


def test_the_sign_combinations_of_table_6_1(butterfly):
    """The thesis decomposes the configuration space into "16 components, one for each
    combination of signs" (§6.3): the 2⁴ sign combinations, of which its Table 6.1 colours
    eleven. The traced pieces carry exactly those eleven η; a combination's curve may
    consist of several pieces (17 pieces in all), each a connected arc of it."""
    _, traced = butterfly
    assert {sign_index(piece.middle, ETA) for piece in traced.pieces} == TABLE_6_1


def test_traced_pieces_hold_every_slice_configuration(butterfly):
    """An independent check: at 40 random values of s2,4 every configuration that the
    slice root finder lists lies on a traced piece of its sign vector."""
    system, traced = butterfly
    scale = np.array(system.upper)
    rng = np.random.default_rng(19)
    found = [point for u in rng.uniform(17, system.upper[0], 40) for point in configurations_at(system, u)]
    assert len(found) > 200
    assert all(any(_on_piece(_scaled(point, scale), piece, scale, 1 / 200)
                   for piece in traced.pieces if piece.signs == point.signs) for point in found)


def test_a_four_bar_is_ranges_of_one_distance():
    """A Grashof four-bar (crank 1, coupler 3, rocker 3, frame 3.5): one distance, two
    oriented areas; each piece a range of the diagonal on one sign vector, its joints'
    coupler curve continuous."""
    scene_data = {"ground": "frame", "links": [
        {"name": "frame", "joints": {"P1": [0, 0], "P4": ["7/2", 0]}},
        {"name": "crank", "joints": ["P1", "P2"], "squared_length": 1},
        {"name": "coupler", "joints": ["P2", "P3"], "squared_length": 9},
        {"name": "rocker", "joints": ["P3", "P4"], "squared_length": 9}]}
    from baranov.scene import scene_from_dict

    system = one_dof_system(scene_from_dict(scene_data))
    traced = trace(system, steps=200)
    assert len(system.plan.parameters) == 1 and len(system.plan.free_sign_triangles) == 2
    assert traced.pieces and not traced.jumps
    assert max(point.max_residual for piece in traced.pieces for point in piece.points) < 1e-9


def test_trace_command(capsys, tmp_path):
    example = str(EXAMPLES / "double-butterfly.json")
    args = ["trace", example, "--parameter", "P2,P4", "--parameter", "P1,P6", "--eta", "P2,P4,P10;P1,P3,P6;P1,P6,P5;P4,P9,P7"]
    assert main([*args, "--plot", str(tmp_path / "trace.png"), "--steps", "200"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"{example}: ") and "pieces in (s2,4, s1,6)" in out
    assert (tmp_path / "trace.png").read_bytes().startswith(b"\x89PNG")
    for bad, message in [(["trace", str(EXAMPLES / "7-B1.json")], "this chain is rigid: its assembly modes"),
                         ([*args, "--eta", "P1,P2"], "--eta P1,P2: triangles of three joints"),
                         ([*args[:2], "--tracer", "P99"], "--tracer P99: no such joint"),
                         ([*args[:2], "--fixed", "nope"], "link nope: no such link to fix")]:
        assert main(bad) == 2
        assert message in capsys.readouterr().err


def test_trace_command_gives_exact_range_ends(capsys):
    """One parameter: the summary says how many pieces the exact ranges certify, and the
    JSON gives each piece's ends exactly (crank 2, coupler 6: s1,3 from 16 to 64)."""
    import json

    example = str(EXAMPLES / "four-bar-coupler-point.json")
    assert main(["trace", example]) == 0
    assert "exact ranges: 4 of 4 pieces certified (one connected range each, ends exact), 0 ranges not traced" in (
        capsys.readouterr().out)
    assert main(["trace", example, "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    first = result["pieces"][0]["exact_range"]
    assert (first["low"]["polynomial"], first["high"]["polynomial"]) == ([-16, 1], [-64, 1])
    assert first["low"]["value"].startswith("16.0000000000") and first["low"]["flat"] == [["P1", "P2", "P3"]]
    assert (result["untraced_ranges"], result["undecided_ranges"]) == ([], [])


def _grubler_cases():
    from baranov.enumerate.crosscheck import find_geng

    if find_geng() is None:
        return []
    from baranov.enumerate.grubler import grubler_chains

    chains = [(links, n, chain) for links in (4, 6, 8) for n, chain in enumerate(grubler_chains(links))]
    # the slowest, 8-2 and 8-7 (two distances), 3.5 s and 2.4 s alone (28 s and 20 s before
    # the curve was followed in joint space)
    return [pytest.param(chain, seed, id=f"{links}-{n}-seed{seed}") for links, n, chain in chains
            for seed in range(2 if links < 8 else 1)]


@pytest.mark.parametrize(("chain", "seed"), _grubler_cases())
def test_traced_pieces_hold_random_configurations(chain, seed):
    """Every Grübler chain to eight links, dimensions from a random integer configuration (fixed link as drawn): the drawn
    configuration lies on a traced piece, and so does every configuration of 12
    independent slices of the first parameter; every traced point verifies, and no joint
    jumps. (With 20 starting slices instead of the default 50, 8-2 missed the drawn
    configuration: a piece narrower than the slices' spacing, not reached from another.)"""
    from baranov.scene.instances import generic_integer_configuration, scene_of

    rng = np.random.default_rng([19, seed])
    drawn = generic_integer_configuration(chain, rng)
    scene = scene_of(chain, drawn)
    system = one_dof_system(scene)
    traced = trace(system)
    scale = np.array(system.upper)
    assert not traced.jumps
    assert max(point.max_residual for piece in traced.pieces for point in piece.points) < 1e-9

    def on_trace(point) -> bool:
        if len(system.parameter_names) == 1:  # a range per sign vector: between its ends
            value = point.parameters[system.parameter_names[0]]
            return any(min(p.parameters[system.parameter_names[0]] for p in piece.points) - 1e-6 * scale[0] <= value
                       <= max(p.parameters[system.parameter_names[0]] for p in piece.points) + 1e-6 * scale[0]
                       for piece in traced.pieces if piece.signs == point.signs)
        return any(_on_piece(_scaled(point, scale), piece, scale, 1 / 200)
                   for piece in traced.pieces if piece.signs == point.signs)

    first = system.plan.parameters[0]
    value = float(sum((drawn[first[0]][k] - drawn[first[1]][k]) ** 2 for k in range(2)))
    at_drawn = [p for p in configurations_at(system, value)
                if max(math.dist(p.joints[j], tuple(map(float, drawn[j]))) for j in drawn) < 1e-6]
    assert at_drawn and all(on_trace(p) for p in at_drawn)
    for u in rng.uniform(0, system.upper[0], 12):
        assert all(on_trace(p) for p in configurations_at(system, u))
    if len(system.parameter_names) == 1:
        _assert_ranges_certified(system, traced)


def _assert_ranges_certified(system, traced) -> None:
    """One parameter: every traced piece is an exact range of its branch (ends within
    1e-9 of the range, one connected range), and every exact range is traced."""
    from baranov.motion.exact_ranges import certified_pieces, exact_ranges

    found = exact_ranges(system)
    matched, untraced = certified_pieces(system, traced, found)
    assert found.undecided == ()
    assert all(r is not None for r in matched), [n for n, r in enumerate(matched) if r is None]
    assert untraced == [], [(r.signs, r.low.digits(12), r.high.digits(12)) for r in untraced]


def _one_parameter_chains() -> list:
    from baranov.enumerate.crosscheck import find_geng
    from baranov.enumerate.grubler import grubler_chains
    from baranov.planner import one_dof_plans

    if find_geng() is None:
        return []
    return [chain for links in (4, 6, 8) for chain in grubler_chains(links)
            if one_dof_plans(chain)[0].number_of_parameters == 1]


@pytest.mark.slow  # 24 s (2026-11-28)
@settings(max_examples=15, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), pick=st.integers(0, 2**16))
def test_exact_ranges_are_the_traced_pieces(seed, pick):
    """Random integer dimensions of a random one-parameter Grübler chain (the four-bar,
    both six-bars, twelve eight-bars): the ranges computed exactly from the radicands'
    norms (motion/exact_ranges.py) are exactly the traced pieces, each certified one
    connected range. Before the window search of the ranges, eight-bar 12 of
    docs/stability.md had an exact range 0.0011 wide that no piece traced."""
    from baranov.scene.instances import generic_integer_configuration, scene_of

    chains = _one_parameter_chains()
    if not chains:
        pytest.skip("geng not installed")
    chain = chains[pick % len(chains)]
    system = one_dof_system(scene_of(chain, generic_integer_configuration(chain, np.random.default_rng(seed))))
    _assert_ranges_certified(system, trace(system))


def test_exact_ranges_need_one_parameter_and_exact_dimensions(butterfly):
    from baranov.motion.exact_ranges import exact_ranges
    from baranov.solvers.exact import ExactMethodError

    system, _ = butterfly
    with pytest.raises(ValueError, match="parameters s2,4, s1,6: exact ranges need a one-parameter space"):
        exact_ranges(system)
    inexact = dict(FOUR_BAR, links=[dict(link) for link in FOUR_BAR["links"]])
    inexact["links"][1]["squared_length"] = 4.5
    with pytest.raises(ExactMethodError, match="a float was given"):
        exact_ranges(one_dof_system(scene_from_dict(inexact)))


# --- coupler-curve degrees (beyond the thesis; motion/coupler_curves.py) ---------------

needs_msolve = pytest.mark.skipif(__import__("baranov.solvers.msolve", fromlist=["find_msolve"]).find_msolve() is None,
                                  reason="msolve binary not installed (make installs it)")
FOUR_BAR = {"ground": "frame", "links": [
    {"name": "frame", "joints": {"P1": [0, 0], "P4": [7, 0]}},
    {"name": "crank", "joints": ["P1", "P2"], "squared_length": 4},
    {"name": "coupler", "joints": ["P2", "P3"], "squared_length": 36},
    {"name": "rocker", "joints": ["P3", "P4"], "squared_length": 25}]}


@needs_msolve
def test_four_bar_coupler_curves_are_sextics():
    """Thesis §6.1: a point of the four-bar's coupler draws a sextic, the coupler's joints
    circles; over two primes alike. The ground link's points and a fixed joint draw
    nothing, and say so."""
    from fractions import Fraction

    from baranov.motion import CouplerCurveError, coupler_curve_degree
    from baranov.scene import scene_from_dict

    scene = scene_from_dict(FOUR_BAR)
    for prime in (2147483629, 2147483587):
        assert coupler_curve_degree(scene, "coupler", (Fraction(1, 3), Fraction(2, 5)), prime=prime) == 6
    assert coupler_curve_degree(scene, "coupler", seed=4) == 6
    assert [coupler_curve_degree(scene, "coupler", joint=j) for j in ("P2", "P3")] == [2, 2]
    with pytest.raises(CouplerCurveError, match="link frame: the ground link"):
        coupler_curve_degree(scene, "frame")
    with pytest.raises(CouplerCurveError, match="does not move along a curve"):
        coupler_curve_degree(scene, "crank", joint="P1")
    with pytest.raises(CouplerCurveError, match="joint P4: not a joint of link coupler"):
        coupler_curve_degree(scene, "coupler", joint="P4")


#: Computed (motion/coupler_curves.py, random integer configurations drawn with seed
#: [19, 6, n], two primes alike): the degrees of a generic point's coupler curve on each
#: moving link, for each fixed link, sorted; six-bar chain 0 (ternary links apart:
#: Stephenson) and 1 (ternary links adjacent: Watt).
SIX_BAR_DEGREES = {
    0: [[2, 2, 2, 6, 18], [2, 2, 2, 6, 18], [2, 2, 6, 16, 16], [2, 2, 6, 16, 16], [2, 2, 16, 16, 18],
        [2, 2, 16, 16, 18]],
    1: [[2, 2, 2, 6, 6], [2, 2, 2, 6, 6], [2, 2, 6, 14, 16], [2, 2, 6, 14, 16], [2, 2, 6, 14, 16],
        [2, 2, 6, 14, 16]],
}


@needs_msolve
@pytest.mark.parametrize("index", [0, 1], ids=["stephenson", "watt"])
def test_six_bar_coupler_curve_degrees(index):
    """Every kinematic inversion of both six-bar chains: the degree of a generic point's
    curve on each moving link (a Stephenson six-bar reaches 18, a Watt six-bar 16; a
    ternary fixed link of the Watt chain leaves two stacked four-bars: sextics)."""
    from baranov.enumerate.crosscheck import find_geng
    from baranov.enumerate.grubler import grubler_chains
    from baranov.motion import coupler_curve_degree
    from baranov.scene.instances import generic_integer_configuration, scene_of

    if find_geng() is None:
        pytest.skip("geng not installed")
    chain = grubler_chains(6)[index]
    drawn = generic_integer_configuration(chain, np.random.default_rng([19, 6, index]))
    found = []
    for ground in range(6):
        scene = scene_of(chain, drawn, ground=ground)
        found.append(sorted(coupler_curve_degree(scene, link.name, seed=2) for link in scene.links
                            if link.name != scene.ground))
    assert sorted(found) == SIX_BAR_DEGREES[index]


@pytest.mark.slow  # 21 s (2026-11-28)
@needs_msolve
def test_double_butterfly_coupler_curves():
    """Thesis §6.1 cites degree up to 48 for the double butterfly's coupler curves: a
    generic point of the coupler triangle P6 P5 P9 draws a curve of degree 48 with the
    thesis's dimensions; its joint P9 one of degree 40 (the slow test: the floating
    binary links' points reach 52)."""
    from baranov.motion import coupler_curve_degree

    scene = load_scene(EXAMPLES / "double-butterfly.json")
    assert coupler_curve_degree(scene, "t6-5-9", seed=1) == 48
    assert coupler_curve_degree(scene, "t6-5-9", joint="P9") == 40


@needs_msolve
@pytest.mark.slow
def test_double_butterfly_binary_links_reach_52():
    """A generic point of the floating binary link P3 P6 (or P4 P7) of the double
    butterfly draws a curve of degree 52, above the 48 the thesis cites; with the
    thesis's dimensions and with a random integer configuration, over two primes."""
    from baranov.motion import coupler_curve_degree
    from baranov.scene.instances import generic_integer_configuration, scene_of
    from baranov.topology import joints_of_links

    example = load_scene(EXAMPLES / "double-butterfly.json")
    assert coupler_curve_degree(example, "b36", seed=1) == 52
    chain = example.chain
    ground = next(k for k, joints in enumerate(joints_of_links(chain)) if set(joints) == {"P1", "P2", "P10"})
    scene = scene_of(chain, generic_integer_configuration(chain, np.random.default_rng(5)), ground=ground)
    binary = next(link.name for link in scene.links if set(link.joints) == {"P3", "P6"})
    for prime in (2147483629, 2147483587):
        assert coupler_curve_degree(scene, binary, seed=3, prime=prime) == 52


@needs_msolve
def test_trace_command_prints_coupler_curve_degrees(capsys, tmp_path):
    import json

    path = tmp_path / "four-bar.json"
    path.write_text(json.dumps(FOUR_BAR))
    assert main(["trace", str(path), "--tracer", "P3", "--degree", "--steps", "50"]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == ("coupler-curve degrees: P3 2, crank (generic point) 2, "
                                                        "coupler (generic point) 6, rocker (generic point) 2")
    assert main(["trace", str(path), "--tracer", "P1", "--degree", "--steps", "50", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["coupler_curve_degrees"]["P1"] == "fixed"


def test_trace_command_drives_a_crank(capsys, tmp_path):
    """`--input P1,P4,P2`: the crank angle at P1 from P4 to P2 at 36 values round the
    circle; a crank-rocker's crank turns fully, so both of its pieces (the two
    assembly modes) meet every value, each configuration verified."""
    import json

    path = tmp_path / "four-bar.json"
    path.write_text(json.dumps(_four_bar(*GRASHOF["crank-rocker"])))
    assert main(["trace", str(path), "--input", "P1,P4,P2", "--json"]) == 0
    driven = json.loads(capsys.readouterr().out)["driven"]
    values = sorted(round((v + 180) % 360 - 180, 6) for branch in driven for v in branch["values"])
    assert values == sorted([round(-180 + 10 * k, 6) for k in range(36)] * 2)
    for bad, message in [("P1,P9", "--input P1,P9: joint P9: no such joint"),
                         ("P1,P1,P2", "--input P1,P1,P2: a joint named twice")]:
        assert main(["trace", str(path), "--input", bad]) == 2
        assert message in capsys.readouterr().err


def test_kinematic_inversion_fixes_another_link(butterfly):
    """Thesis §6.3.1: with the coupler triangle P6 P5 P9 fixed, every traced configuration
    is moved rigidly into its frame (P6 at the origin, P5 on the x axis): its joints stay
    put, every link dimension is kept, and P1, pinned to P5 by the binary link P1 P5,
    draws arcs of the circle of radius √145 about P5."""
    from baranov.motion.inversion import InversionError, inverted

    system, traced = butterfly
    turned = inverted(traced, system.scene, "t6-5-9")
    points = [point for piece in turned.pieces for point in piece.points]
    first = points[0].joints
    assert first["P6"] == (0.0, 0.0) and abs(first["P5"][1]) < 1e-12 and first["P5"][0] > 0
    assert all(math.dist(p.joints[j], first[j]) < 1e-9 for p in points for j in ("P6", "P5", "P9"))
    originals = [point for piece in traced.pieces for point in piece.points]
    assert all(abs(math.dist(p.joints[a], p.joints[b]) - math.dist(q.joints[a], q.joints[b])) < 1e-9
               for p, q in zip(points[::50], originals[::50], strict=True) for a in p.joints for b in p.joints)
    assert all(abs(math.dist(p.joints["P1"], first["P5"]) - math.sqrt(145)) < 1e-9 for p in points)
    with pytest.raises(InversionError, match="link nope: no such link to fix"):
        inverted(traced, system.scene, "nope")


# --- the motion driven by an input (motion/driving.py) --------------------------------

def _driven_equals_rigid_solves(entries: dict, rng, values: int = 4) -> int:
    """At ``values`` random crank angles within the traced range: the configurations the
    driven motion lists are, mode for mode, the numeric backend's of the rigidified
    chain; returns how many configurations were compared."""
    from baranov.motion.driving import crank_of, distinct_configurations, driven_motion, input_value, rigidified
    from baranov.scene import scene_from_dict
    from baranov.solvers import solve
    from baranov.solvers.msolve import compare_modes

    scene = scene_from_dict(entries)
    driver = crank_of(scene)
    system = one_dof_system(scene)
    traced = trace(system)
    reached = [input_value(driver, point) for piece in traced.pieces for point in piece.points]
    angles = rng.uniform(min(reached), max(reached), values)
    branches = driven_motion(system, traced, driver, angles)
    compared = 0
    for angle in angles:
        found = [point.joints for point in distinct_configurations(branches, angle, 360)]
        rigid = rigidified(scene, driver, angle)
        modes = [mode.joints for mode in solve(rigid, method="numeric").assembly_modes]
        assert compare_modes(found, modes)[:2] == (0, 0), (angle, len(found), len(modes))
        assert all(point.max_residual < 1e-8 for branch in branches for point in branch.points)
        compared += len(modes)
    return compared


def _four_bar(ground: int, crank: int, coupler: int, rocker: int) -> dict:
    return {"ground": "frame", "links": [
        {"name": "frame", "joints": {"P1": [0, 0], "P4": [ground, 0]}},
        {"name": "crank", "joints": ["P1", "P2"], "squared_length": crank ** 2},
        {"name": "coupler", "joints": ["P2", "P3"], "squared_length": coupler ** 2},
        {"name": "rocker", "joints": ["P3", "P4"], "squared_length": rocker ** 2}]}


#: Four-bars of every Grashof class (s + l against p + q; s the shortest, l the longest).
GRASHOF = {"crank-rocker": (7, 2, 6, 5), "double-crank": (2, 6, 7, 5), "double-rocker": (6, 5, 2, 7),
           "triple-rocker": (5, 3, 4, 7), "change-point": (5, 2, 4, 3)}


@pytest.mark.parametrize("kind", GRASHOF)
def test_driven_four_bars_of_every_grashof_class(kind):
    """The crank driven over its range: at random angles, every configuration of the
    driven motion is one of the rigidified four-bar's (the numeric backend), and none is
    missing."""
    assert _driven_equals_rigid_solves(_four_bar(*GRASHOF[kind]), np.random.default_rng(len(kind)), 6) > 0


@settings(max_examples=12, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), six_bar=st.integers(0, 1))
def test_driven_six_bars_equal_the_rigidified_chains(seed, six_bar):
    """Random Watt and Stephenson six-bars (random integer configurations, a crank
    pinned to the fixed link): the driven motion holds exactly the rigidified chain's
    configurations at random crank angles."""
    from baranov.enumerate.crosscheck import find_geng
    from baranov.enumerate.grubler import grubler_chains

    if find_geng() is None:
        pytest.skip("geng not installed")
    rng = np.random.default_rng(seed)
    _driven_equals_rigid_solves(_with_a_crank(grubler_chains(6)[six_bar], rng), rng)


def _with_a_crank(chain, rng) -> dict:
    """A scene (JSON) of ``chain`` from a random integer configuration, its fixed link the
    first with a binary link pinned to it (a crank)."""
    from baranov.motion.driving import crank_of
    from baranov.scene import scene_from_dict
    from baranov.scene.instances import generic_integer_configuration, instance_dict

    drawn = generic_integer_configuration(chain, rng)
    for ground in range(chain.number_of_links):
        entries = instance_dict(chain, drawn, ground)
        if crank_of(scene_from_dict(entries)) is not None:
            return entries
    raise AssertionError("no link with a crank pinned to it")


def test_driven_double_butterfly_equals_the_rigidified_chains():
    """d = 2 (under 2 s; 23 s before the curve was followed in joint space): the double butterfly
    driven by the angle of P1P5 at P1 from P2, at six random angles within its range:
    the rigidified seven-link chains' modes, all and only."""
    import json

    entries = json.loads((EXAMPLES / "double-butterfly.json").read_text())
    assert _driven_equals_rigid_solves(entries, np.random.default_rng(6), 6) > 0


@pytest.mark.parametrize("index", range(16))
def test_driven_eight_bars_equal_the_rigidified_chains(index):
    """Every eight-bar Grübler chain, a random integer configuration with a crank pinned
    to the fixed link (measured: 0.5-2.5 s each; 0.4-25 s before the curve was followed in
    joint space)."""
    from baranov.enumerate.crosscheck import find_geng
    from baranov.enumerate.grubler import grubler_chains

    if find_geng() is None:
        pytest.skip("geng not installed")
    rng = np.random.default_rng([19, 8, index])
    _driven_equals_rigid_solves(_with_a_crank(grubler_chains(8)[index], rng), rng)


def _eight_bar_with_a_crank(index: int):
    """Eight-bar ``index`` as the fixed-angle bench of docs/stability.md draws it (seed
    [19, 8, index]), its scene and crank."""
    from baranov.enumerate.crosscheck import find_geng
    from baranov.enumerate.grubler import grubler_chains
    from baranov.motion.driving import crank_of

    if find_geng() is None:
        pytest.skip("geng not installed")
    scene = scene_from_dict(_with_a_crank(grubler_chains(8)[index], np.random.default_rng([19, 8, index])))
    return scene, crank_of(scene)


def _rigid_modes(scene, driver, angle: float) -> list[dict]:
    from baranov.motion.driving import rigidified
    from baranov.solvers import solve

    return [mode.joints for mode in solve(rigidified(scene, driver, angle), method="numeric").assembly_modes]


def test_a_window_of_the_range_between_the_crank_in_line_and_an_edge():
    """Eight-bar 12 (d = 1): on branches (−, +, −, ±) the domain of s2,10 includes a
    window 0.0011 wide, from where the crank's triangle with the fixed link is flat (the
    crank at 180°) to where P9 P7 P6 is; the range samples (4.7 apart there) missed it,
    and the driven motion lost one of the six configurations at 180°. Now the window
    search of the numeric backend finds it, and range ends are placed with their flat
    triangle flat (the crank at exactly 180°, not 179.9987°)."""
    from baranov.motion.driving import distinct_configurations, driven_motion, input_value
    from baranov.solvers.msolve import match_configurations

    scene, driver = _eight_bar_with_a_crank(12)
    system = one_dof_system(scene)
    traced = trace(system)
    windows = [piece for piece in traced.pieces if abs(piece.points[-1].parameters["s2,10"]
                                                       - piece.points[0].parameters["s2,10"]) < 0.01]
    assert len(windows) == 2
    assert all(any(abs(abs(input_value(driver, end)) - 180) < 1e-9 for end in (piece.points[0], piece.points[-1]))
               for piece in windows)
    found = [p.joints for p in distinct_configurations(driven_motion(system, traced, driver, [180.0]), 180.0, 360)]
    modes = _rigid_modes(scene, driver, 180.0)
    assert len(modes) == 6
    assert match_configurations(found, modes) == ([], [])


def test_a_crossing_where_the_curve_bends_past_the_domain():
    """Eight-bar 9 (d = 2), two neighbouring traced points of piece (+, −, +, −) at
    (s1,10, s3,10) ≈ (0.634, 2685.5) and (0.897, 2679.5), the crank at 176.5° and
    −177.5°: their linear interpolation lies outside the domain (P10 is 0.87 from P1), so
    Newton's method had no start, and the configuration at 180° was missed. The stretch
    is now split at points of the curve until Newton's method converges."""
    from baranov.motion.configuration_space import slice_configurations
    from baranov.motion.driving import distinct_configurations, driven_motion, input_value
    from baranov.motion.tracing import Piece, Trace
    from baranov.solvers.msolve import match_configurations

    scene, driver = _eight_bar_with_a_crank(9)
    system = one_dof_system(scene)
    signs = (1, -1, 1, -1)
    ends = []
    for s1_10, s3_10 in ((0.633698, 2685.544442), (0.897347, 2679.461168)):
        near = np.linspace(s3_10 - 1, s3_10 + 1, 41)
        ends.append(min(slice_configurations(system, s1_10, near, np.array([signs])),
                        key=lambda point, s3_10=s3_10: abs(point.parameters["s3,10"] - s3_10)))
    assert [round(input_value(driver, point), 1) for point in ends] == [176.5, -177.5]
    stretch = Trace((Piece(signs, tuple(ends)),), ())
    found = [p.joints for p in distinct_configurations(driven_motion(system, stretch, driver, [180.0]), 180.0, 360)]
    modes = _rigid_modes(scene, driver, 180.0)
    missed, spurious = match_configurations(found, modes)
    assert (len(found), len(modes), len(missed), spurious) == (1, 2, 1, [])  # the other is on another piece


def test_a_crank_turns_round_through_the_branch_points(capsys, tmp_path):
    """examples/stephenson-six-bar.json: its crank-rocker's crank turns fully, so the
    motion followed from one piece on through the branch points meets each of 36 crank
    angles once and comes back, no joint moving more than a crank's swing of 10° allows
    between frames; `--animate` draws it (36 frames), and asks for --input."""
    from PIL import Image

    from baranov.motion.driving import driven_motion, followed

    scene = load_scene(EXAMPLES / "stephenson-six-bar.json")
    system = one_dof_system(scene)
    traced = trace(system)
    (crank,) = scene.inputs
    driven = driven_motion(system, traced, crank, -180 + 10 * np.arange(36))
    motion = followed(traced, driven, max(driven, key=lambda branch: len(branch.points)).piece)
    assert sorted(round((v + 180) % 360 - 180) for v in motion.values) == list(range(-180, 180, 10))
    frames = list(motion.points) + [motion.points[0]]
    assert max(math.dist(a.joints[j], b.joints[j]) for a, b in zip(frames[:-1], frames[1:], strict=True)
               for j in a.joints) < 1.5
    path = tmp_path / "motion.gif"
    args = ["trace", str(EXAMPLES / "stephenson-six-bar.json"), "--tracer", "P5"]
    assert main([*args, "--input", "crank", "--animate", str(path)]) == 0
    assert Image.open(path).n_frames == 36 and Image.open(path).size == (640, 640)
    capsys.readouterr()
    assert main([*args, "--animate", str(path)]) == 2
    assert "give --input too" in capsys.readouterr().err


def _configurations_at(entries: dict, angle: float) -> tuple[list[dict], list[dict]]:
    """The driven motion's configurations of a four-bar (crank at P1 from P4 to P2) at
    ``angle``, each once (a branch point's belongs to every piece meeting there), and the
    numeric backend's modes of the four-bar rigidified there."""
    from baranov.motion.driving import distinct_configurations, driven_motion, rigidified
    from baranov.scene import SceneInput, scene_from_dict
    from baranov.solvers import solve

    scene = scene_from_dict(entries)
    system = one_dof_system(scene)
    driver = SceneInput("crank", "angle", ("P1", "P4", "P2"))
    found = [point.joints for point in distinct_configurations(driven_motion(system, trace(system), driver, [angle]),
                                                               angle, 360)]
    rigid = rigidified(scene, driver, angle)
    return found, [mode.joints for mode in solve(rigid, method="numeric").assembly_modes]


def test_a_dead_point_is_reached_to_rounding():
    """Stability (issue 19): a double-rocker four-bar's crank swings to arccos(−1/3) =
    109.4712206° (coupler and rocker in line), a local extremum of the input inside a
    piece, between two samples (109.4633° was the highest sampled). The driven motion
    refines it: the extreme listed is arccos(−1/3) to 1e-9°; 1e-5° below it both
    configurations are there (the numeric backend's two), 1e-5° above none."""
    from baranov.motion.driving import _with_extrema, input_value
    from baranov.scene import SceneInput, scene_from_dict
    from baranov.solvers.msolve import compare_modes

    entries = _four_bar(*GRASHOF["double-rocker"])
    system = one_dof_system(scene_from_dict(entries))
    driver = SceneInput("crank", "angle", ("P1", "P4", "P2"))
    from baranov.motion.continuation import linkage_curve

    curve = linkage_curve(system.scene, system.plan.free_sign_triangles)
    pieces = [_with_extrema(system, curve, driver, piece) for piece in trace(system).pieces]
    dead = math.degrees(math.acos(-1 / 3))
    assert abs(max(input_value(driver, p) for piece in pieces for p in piece.points) - dead) < 1e-9
    below, above = _configurations_at(entries, dead - 1e-5), _configurations_at(entries, dead + 1e-5)
    assert len(below[0]) == 2 and compare_modes(*below) == (0, 0, 0)
    assert above == ([], [])


def test_a_change_point_four_bar_through_its_singular_configuration():
    """Stability (issue 19): the change-point four-bar (2 + 5 = 4 + 3) passes through a
    configuration with every joint in line at a crank angle of 180°, where two branches
    cross: one configuration there, listed once, as the numeric backend lists it; two at
    179° and at −179°."""
    from baranov.solvers.msolve import compare_modes

    entries = _four_bar(*GRASHOF["change-point"])
    for angle, count in ((180.0, 1), (179.0, 2), (-179.0, 2)):
        found, modes = _configurations_at(entries, angle)
        assert len(found) == count and compare_modes(found, modes) == (0, 0, 0), angle


def test_rigidified_needs_a_crank():
    from baranov.motion.driving import rigidified
    from baranov.scene import SceneError, SceneInput, scene_from_dict

    scene = scene_from_dict(_four_bar(*GRASHOF["crank-rocker"]))
    for driver in (SceneInput("stroke", "distance", ("P1", "P3")), SceneInput("knee", "angle", ("P2", "P1", "P3"))):
        with pytest.raises(SceneError, match=f"input {driver.name}: not a crank"):
            rigidified(scene, driver, 30.0)
    assert rigidified(scene, SceneInput("crank", "angle", ("P1", "P4", "P2")), 90.0).world["P2"] == \
        pytest.approx((0.0, 2.0))


def test_a_tracer_point_follows_the_link_it_is_on(capsys, tmp_path):
    """A tracer point placed where a joint of its link is (P5 of the Stephenson six-bar's
    coupler, given by coordinates; P3 of the binary rocker, given by its squared length,
    whose frame has P3 at the origin and P4 on +x) draws that joint's path, at every
    traced and driven configuration, in the JSON output too; one off the joints keeps its
    distances to the link's joints."""
    import json

    scene = json.loads((EXAMPLES / "stephenson-six-bar.json").read_text())
    scene["tracers"] = [{"name": "C5", "link": "coupler", "at": [2, 4]},
                        {"name": "C3", "link": "rocker", "at": [0, 0]},
                        {"name": "C", "link": "coupler", "at": ["3/2", -1]}]
    path = tmp_path / "six-bar.json"
    path.write_text(json.dumps(scene))
    assert main(["trace", str(path), "--input", "crank", "--grid", "12", "--steps", "60", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    points = [p for piece in result["pieces"] for p in piece["points"]] + [p for b in result["driven"] for p in b["points"]]
    assert len(points) > 100 and all(set(p["tracers"]) == {"C5", "C3", "C"} and "C" not in p["joints"] for p in points)
    for p in points:
        joints, tracers = p["joints"], p["tracers"]
        assert math.dist(tracers["C5"], joints["P5"]) < 1e-9 and math.dist(tracers["C3"], joints["P3"]) < 1e-9
        # (3/2, -1) in the coupler's frame P2 (0, 0), P3 (6, 0): squared distances 13/4 and 85/4
        assert abs(math.dist(tracers["C"], joints["P2"]) ** 2 - 13 / 4) < 1e-9
        assert abs(math.dist(tracers["C"], joints["P3"]) ** 2 - 85 / 4) < 1e-9


@needs_msolve
def test_a_coupler_point_draws_the_sextic(capsys):
    """examples/four-bar-coupler-point.json: the coupler point C off the coupler's line
    draws a curve of degree 6 (the four-bar's tricircular sextic), exactly as a generic
    point of the coupler."""
    assert main(["trace", str(EXAMPLES / "four-bar-coupler-point.json"), "--degree", "--steps", "50"]) == 0
    assert capsys.readouterr().out.splitlines()[-1].startswith("coupler-curve degrees: C 6, ")


def test_tracer_points_are_validated():
    """Each mistake in a scene's "tracers" is one SceneError naming the tracer."""
    import json

    from baranov.scene import SceneError

    base = json.loads((EXAMPLES / "four-bar-coupler-point.json").read_text())
    for tracers, message in [
        ({"name": "C"}, "tracers: expected a list"),
        ([{"link": "coupler", "at": [1, 2]}], "tracer #1: expected an object with a \"name\""),
        ([{"name": "P2", "link": "coupler", "at": [1, 2]}], "tracer P2: name already used"),
        ([{"name": "C", "link": "coupler", "at": [1, 2]}, {"name": "C", "link": "crank", "at": [0, 1]}],
         "tracer C: name already used"),
        ([{"name": "C", "link": "cupler", "at": [1, 2]}], "tracer C: link 'cupler': no such link"),
        ([{"name": "C", "link": "coupler", "at": [1]}], "tracer C: \"at\" needs the point's coordinates"),
        ([{"name": "C", "link": "coupler", "at": ["one", 2]}], "tracer C, at"),
        ([{"name": "C", "link": "coupler", "at": [1, 2], "colour": "red"}], "tracer C: unknown key 'colour'"),
    ]:
        with pytest.raises(SceneError, match=re.escape(message)):
            scene_from_dict({**base, "tracers": tracers})


def test_trace_pictures_name_every_colour_they_draw():
    """The four-bar with a coupler point (one parameter): each sign vector of the plan is
    a row of the configuration space, labelled with it and its η, drawn in one colour, and
    the coupler curve of a piece has its piece's colour (issue 57: eight colours had been
    drawn under a legend of η = 0 … 3)."""
    from matplotlib.colors import to_hex

    from baranov.motion.drawing import trace_figure
    from baranov.motion.tracer_paths import traced_with_tracer_points
    from baranov.solvers.modes import signs_text

    scene = load_scene(EXAMPLES / "four-bar-coupler-point.json")
    system = one_dof_system(scene)
    traced = traced_with_tracer_points(scene, trace(system))
    figure = trace_figure(system, traced, ["C"])
    space, paths, _ = figure.axes
    labels = [tick.get_text() for tick in space.get_yticklabels()]
    assert sorted(label.split("(")[1].rstrip(")") for label in labels) == \
        sorted({signs_text(piece.signs) for piece in traced.pieces})
    bars = [line for line in space.get_lines() if line.get_linewidth() > 3]
    colour_of_row = {int(round(line.get_ydata()[0])): to_hex(line.get_color()) for line in bars}
    assert len(set(colour_of_row.values())) == len(labels)
    curves = [to_hex(line.get_color()) for line in paths.get_lines() if line.get_linestyle() == "-"]
    assert sorted(set(curves)) == sorted(set(colour_of_row.values()))


def test_trace_joints_prints_the_driven_configurations(capsys):
    """``trace --input crank --joints`` prints each driven configuration's coordinates,
    those of ``--json``; without --input it is refused in one line (exit 2)."""
    import json

    path = str(EXAMPLES / "four-bar-coupler-point.json")
    assert main(["trace", path, "--input", "crank", "--grid", "4", "--json"]) == 0
    driven = json.loads(capsys.readouterr().out)["driven"]
    assert main(["trace", path, "--input", "crank", "--grid", "4", "--joints"]) == 0
    out = capsys.readouterr().out
    first = driven[0]["points"][0]
    x, y = first["joints"]["P3"]
    assert f"crank = {driven[0]['values'][0]:.6g}°:" in out
    assert f"P3 = ({x:.10g}, {y:.10g})" in out
    assert out.count("crank = ") == sum(len(branch["points"]) for branch in driven)
    assert main(["trace", path, "--joints"]) == 2
    assert capsys.readouterr().err.count("\n") == 1
