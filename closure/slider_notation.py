"""The closure condition of a slider chain in the thesis's notation (thesis §4.1–4.2.4,
paper 003 §3–4): the truss's closure conditions, every distance from a slider P_i to a
joint P_j of one of its two links replaced by d_{i,j} = δ + d_{i′,j} sin α (the oriented
distance of P_j to the axis, thesis §4.1), and the limit δ → ∞ of each slider taken in
turn; which of the thesis's cases applies to each slider is named.

This is the derivation as the thesis writes it; the solvers run its geometric form, the
limits of the bilateration steps (:mod:`.sliders`).
"""

from __future__ import annotations

from collections.abc import Sequence

from baranov.planner import Plan
from baranov.topology import KinematicChain, thesis_subscript
from baranov.topology.chain import natural_sort_key


def _d(joint: str, slider: str, mark: str = "") -> str:
    """d_{j,i} between a joint and a slider, the smaller subscript first as the thesis
    writes them, with ``mark`` on the slider's (d5,9′, d1′,2)."""
    first, second = sorted(((joint, ""), (slider, mark)), key=lambda item: natural_sort_key(item[0]))
    return f"d{thesis_subscript(first[0])}{first[1]},{thesis_subscript(second[0])}{second[1]}"


def slider_case(chain: KinematicChain, plan: Plan, sliders: Sequence[str], slider: str) -> str:
    """Which case of thesis ch. 4 ``slider`` is in ``plan``: at an end of the variable
    segment (§4.2.4), in the reference pair (the frame on its axis), on a link whose joints
    are all sliders (§5.2.1.3), beside another slider of one of its links (§4.2.3), or alone
    (§4.2.2). O(joints)."""
    links = next(joint.links for joint in chain.joints if joint.name == slider)
    for pair in plan.parameters:
        if slider in pair:
            other = pair[0] if pair[1] == slider else pair[1]
            return (f"§4.2.4: it ends the variable segment, so the unknown is t{thesis_subscript(pair[0])},"
                    f"{thesis_subscript(pair[1])}, the oriented distance of {other} to its axis")
    if slider in plan.reference:
        return "the reference pair holds it: the frame sits on its axis (§4.2.4)"
    on_links = [[j.name for j in chain.joints if link in j.links] for link in links]
    if any(len(names) > 2 and all(name in sliders for name in names) for names in on_links):
        return "§5.2.1.3: every joint of one of its non-binary links is a slider"
    if any(name in sliders and name != slider for names in on_links for name in names):
        return "§4.2.3: another slider shares one of its links (the cosine theorem with the angle between the axes)"
    return "§4.2.2: one slider replaces a revolute joint"


def slider_closure_text(chain: KinematicChain, plan: Plan, sliders: Sequence[str]) -> list[str]:
    """The lines that turn the truss's closure conditions (of ``plan``) into the slider
    chain's: per slider its δ, its two points P_i′, P_i″ and their links, its case
    (:func:`slider_case`), the substitutions d_{i,j} = δ + d_{i′,j} sin α_n (α numbered in
    order), the cosine theorem for two sliders of one link, and the order of the limits.
    O(joints²).

    The chain of thesis §4.2.2 (its scene: ``examples/7-B3-slider-P9.json``), whose
    substitutions the thesis prints as d5,9 = δ1 + d5,9′ sin α1, …:

    >>> from baranov.planner.sliders import slider_plan
    >>> from baranov.scene import load_scene
    >>> chain = load_scene("examples/7-B3-slider-P9.json").chain
    >>> for line in slider_closure_text(chain, slider_plan(chain, ["P9"]), ["P9"]):
    ...     print(line)
    P9 (δ1): P9′ on link t569, P9″ on link t789; §4.2.2: one slider replaces a revolute joint
      d5,9 = δ1 + d5,9′ sin α1
      d6,9 = δ1 + d6,9′ sin α2
      d7,9 = δ1 + d7,9″ sin α3
      d8,9 = δ1 + d8,9″ sin α4
    closure: the leading coefficient of each condition as δ1 → ∞
    """
    order = [joint for joint in chain.joints if joint.name in sliders]
    delta = {joint.name: f"δ{n}" for n, joint in enumerate(order, 1)}
    members = {link: [j.name for j in chain.joints if link in j.links] for link in range(chain.number_of_links)}
    lines, angle, distance = [], 0, {}
    for joint in order:
        i = joint.name
        lines.append(f"{i} ({delta[i]}): {i}′ on link {chain.link_name(joint.links[0])}, {i}″ on link "
                     f"{chain.link_name(joint.links[1])}; {slider_case(chain, plan, sliders, i)}")
        for link, mark in zip(joint.links, ("′", "″"), strict=True):
            for j in members[link]:
                if j == i or j in sliders:
                    continue
                angle += 1
                distance[i, j] = f"{delta[i]} + {_d(j, i, mark)} sin α{angle}"
                lines.append(f"  {_d(j, i)} = {distance[i, j]}")
    for link, names in members.items():
        on_link = [name for name in names if name in sliders]
        for first, second in ((a, b) for n, a in enumerate(on_link) for b in on_link[n + 1:]):
            pivot = next((name for name in names if name not in sliders), None)
            if pivot is None:
                lines.append(f"{first}, {second}: the axes meet at the angle link {chain.link_name(link)} fixes "
                             f"(§5.2.1.3)")
                continue
            lines.append(f"s{thesis_subscript(first)},{thesis_subscript(second)} = {_d(pivot, first)}² + "
                         f"{_d(pivot, second)}² − 2 {_d(pivot, first)} {_d(pivot, second)} cos ∠{first}∞{pivot}"
                         f"{second}∞ (§4.2.3; ∠ fixed by link {chain.link_name(link)}: the angle between the axes)")
    limits = " then ".join(f"{delta[joint.name]} → ∞" for joint in order)
    adjacent = any(sum(name in sliders for name in names) > 1 for names in members.values())
    lines.append(f"closure: the leading coefficient of each condition as {limits}"
                 + (" (in this order: the limits are not independent, §4.2.3)" if adjacent else ""))
    return lines
