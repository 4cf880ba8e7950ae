"""The six 3-RPR examples of thesis §5.1.3: a 3-RPR robot with locked legs is a 5/B1
pentad; Γ(T) is its characteristic polynomial in T = s1,5 (§5.1.1).

Where our polynomial differs in form from the printed one, the test says how:
- Example II: the printed Γ(T) has the factor T⁴; ours drops T, because the plan is
  undefined at T = 0 (P1 = P5 is a bilateration base). The two modes there are found with
  another plan (baranov.solvers.coincidence) and the rest of Γ agrees exactly.
- Examples III and IV: ours is the square of the printed polynomial. With coalescent
  (III) or collinear (IV) attachments a free-sign triangle's sign no longer changes the
  closure condition, so the norm over the 2² sign branches counts every root twice; the
  thesis squares once fewer (its Φb = Φc = Φd = 0, Table 5.1).
- Example V has irrational dimensions (400(5 − 2√3)): the exact method refuses it; the
  numeric method finds the four published modes.
"""

from fractions import Fraction
from pathlib import Path

import flint
import pytest

from baranov.scene import load_scene
from baranov.solvers import ExactMethodError, solve
from baranov.solvers.exact.characteristic import characteristic_polynomial

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def scene(name: str):
    return load_scene(EXAMPLES / f"3-RPR-{name}.json")


def gamma(name: str):
    polynomial = characteristic_polynomial(scene(name))
    assert polynomial.variable == "s1,5"
    return polynomial


def monic(coefficients):
    """Monic coefficients, highest degree first."""
    coefficients = [Fraction(c) for c in coefficients]
    return [c / coefficients[0] for c in coefficients]


def flint_poly(coefficients) -> flint.fmpq_poly:
    """A polynomial from coefficients given highest degree first."""
    return flint.fmpq_poly([flint.fmpq(Fraction(c).numerator, Fraction(c).denominator) for c in coefficients[::-1]])


def mode_values(solution) -> list[float]:
    return [round(m.parameters["s1,5"], 4) for m in solution.assembly_modes]


PUBLISHED = {  # Γ(T), highest degree first, as printed in §5.1.3
    "I": [-7738000, 4843775840, -1068953603696, 100805055226688, -4600887845553776, 101331227980892000,
          -876950498856250000],
    "II": [-83200, 5603328, -84934656, 0, 0, 0, 0],
    "III": [10, -592, 7840],
    "IV": [8, -78, 195, -44],
    "VI": [-32, 432, Fraction(-4455, 2), Fraction(39839, 8), Fraction(-339993, 64), Fraction(110565, 32),
           Fraction(-47385, 32)],
}


@pytest.mark.parametrize("name", ["I", "VI"])
def test_gamma_is_the_published_sextic(name):
    assert gamma(name).monic_coefficients() == monic(PUBLISHED[name])


def test_example_ii_gamma_is_the_published_one_without_its_t4_factor():
    ours = flint_poly(gamma("II").monic_coefficients())
    assert ours * flint_poly([1, 0, 0, 0, 0]) == flint_poly(monic(PUBLISHED["II"]))


@pytest.mark.parametrize("name", ["III", "IV"])
def test_gamma_is_the_square_of_the_published_polynomial(name):
    published = flint_poly(monic(PUBLISHED[name]))
    assert flint_poly(gamma(name).monic_coefficients()) == published**2


@pytest.mark.parametrize("method", ["exact", "numeric"])
def test_example_i_double_root_at_49_is_one_configuration(method):
    """§5.1.3.1: the double root T = 49 is a valid configuration (with P1 = (0, 0),
    P2 = (4, 0), P3 = (1, 8): P4 = (−1, 0)), which tangent-half-angle formulations miss;
    the other four roots are complex."""
    solution = solve(scene("I"), method=method)
    assert mode_values(solution) == [49.0]
    assert solution.assembly_modes[0].joints["P4"] == pytest.approx((-1.0, 0.0), abs=1e-6)


@pytest.mark.parametrize("method", ["exact", "numeric"])
def test_example_ii_two_configurations_at_t_zero(method):
    """§5.1.3.2: the quadruple root T = 0 gives two configurations (P5 = P1); T = 23.04
    and 44.3077 one each (Fig. 5.3: four poses)."""
    solution = solve(scene("II"), method=method)
    assert mode_values(solution) == [0.0, 0.0, 23.04, 44.3077]
    for mode in solution.assembly_modes[:2]:
        assert mode.joints["P5"] == pytest.approx(mode.joints["P1"], abs=1e-4)


@pytest.mark.parametrize("method", ["exact", "numeric"])
def test_example_iii_coalescent_attachments(method):
    """§5.1.3.3: s1,3 = 0; roots 20 and 196/5, two poses each (Fig. 5.4). The thesis
    places P1 = P3 = (5, 0), P2 = (0, 0); ours has P1 = (0, 0), P2 = (5, 0), so its P4
    (2, −1) and (6, 3) at T = 20 are ours turned by π about (2.5, 0): (3, 1), (−1, −3)."""
    solution = solve(scene("III"), method=method)
    assert mode_values(solution) == [20.0, 20.0, 39.2, 39.2]
    found = sorted(tuple(round(c, 6) for c in m.joints["P4"]) for m in solution.assembly_modes[:2])
    assert found == [(-1.0, -3.0), (3.0, 1.0)]


@pytest.mark.parametrize("method", ["exact", "numeric"])
def test_example_iv_collinear_attachments(method):
    """§5.1.3.4: roots 1/4, 4 and 11/2 of which 1/4 is outside the feasible interval (5.3);
    Fig. 5.5 lists P4 = (−0.25, ∓0.9682) at T = 4 and P4 = (−1, 0) twice at T = 11/2
    (mirror images in the base line)."""
    solution = solve(scene("IV"), method=method)
    assert mode_values(solution) == [4.0, 4.0, 5.5, 5.5]
    found = sorted(tuple(round(c, 4) for c in m.joints["P4"]) for m in solution.assembly_modes)
    assert found == [(-1.0, 0.0), (-1.0, 0.0), (-0.25, -0.9682), (-0.25, 0.9682)]


def test_example_v_similar_triangles_numeric():
    """§5.1.3.5, Fig. 5.6: T and P4 of the four poses (P1 = (0, 0), P2 = (40, 0) as in the
    thesis)."""
    solution = solve(scene("V"))
    assert mode_values(solution) == [329.4937, 345.1531, 387.5845, 474.3144]
    assert [tuple(round(c, 4) for c in m.joints["P4"]) for m in solution.assembly_modes] == [
        (-0.7943, 1.8355), (1.4501, 1.3774), (1.9805, -0.2787), (1.016, 1.7227)]


def test_example_v_has_irrational_dimensions_for_the_exact_method():
    """The file gives 400(5 − 2√3) as a decimal, read exactly: the base triangle's area is
    then not rational, which the exact method needs (a triangle's frame has its sine)."""
    with pytest.raises(ExactMethodError, match="is not the square of a rational; the exact method needs rational link"):
        solve(scene("V"), method="exact")


def test_example_vi_mirrored_triangles_both_methods_agree():
    """§5.1.3.6 prints the sextic only; its real roots inside the feasible interval are
    the modes, the same for both methods."""
    exact, numeric = solve(scene("VI"), method="exact"), solve(scene("VI"))
    assert mode_values(exact) == mode_values(numeric) == [1.2229, 2.1317]


def test_coincident_joints_are_never_a_bilateration_base():
    from baranov.solvers.coincidence import solvable_plan

    plan = solvable_plan(scene("III"))
    bases = {frozenset(plan.reference)} | {frozenset(step.base) for step in plan.steps}
    assert frozenset(("P1", "P3")) not in bases


def test_zero_length_binary_link_and_coincident_frame_joints_are_refused(tmp_path):
    import json
    import subprocess
    import sys

    data = json.loads((EXAMPLES / "3-RPR-III.json").read_text())
    data["links"][2]["squared_length"] = 0
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(data))
    run = subprocess.run([sys.executable, "-m", "baranov.cli", "solve", str(path)], capture_output=True, text=True)
    assert run.returncode == 2 and run.stderr.count("\n") == 1
    assert "link leg14: squared distance P1,P4 = 0 must be positive" in run.stderr
    data = json.loads((EXAMPLES / "3-RPR-III.json").read_text())
    data["links"][0]["joints"] = ["P1", "P3", "P2"]  # the coincident pair first: it would fix the link's frame
    path.write_text(json.dumps(data))
    run = subprocess.run([sys.executable, "-m", "baranov.cli", "solve", str(path)], capture_output=True, text=True)
    assert run.returncode == 2 and "not its first two" in run.stderr
