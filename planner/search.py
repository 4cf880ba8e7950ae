"""Search for bilateration plans with the fewest parameters (the coupling degree).

Works on the joint graph of any rigid chain (mobility 0, no over-constrained sub-chain):
joints are points; two joints on a common link have a known squared distance.

**Eager location.** From a set of located joints, two rules apply until neither does
(both are forced, so the located set they reach depends only on the starting set):

1. *link step*: a link with two located joints gets all its other joints located from
   those two, with the sign fixed by the link's shape;
2. *cross step*: a joint whose two links each have a located joint is located from them
   (free sign).

Rule 1 has priority, so every joint of a rigid link beyond its first two is located from
two of the link's own joints with the fixed sign: mirror images of links cannot occur
(the spurious roots that a closure condition on a ternary link admits otherwise).

**Search.** A plan is a reference pair (a parameter when its joints share no link) and
a sequence of *parameter steps*, each introducing one unknown distance to locate one more
joint when eager location stops. The minimum number of parameters is found by a
breadth-first search over located sets (each state is a bit mask; eager location is
cached per mask). Then every reference pair and every sequence of parameter joints with
that minimum is explored by branch and bound on
:meth:`~baranov.planner.plan.Plan.ranking_key`: free-sign counts and the sorted profile
of radical depths only grow along a plan, so a partial plan already worse than the k-th
best is cut, and references are visited in the key's own order, so a later reference of
merely equal quality is cut too. The result is the same as ranking every plan. Inside a
plan, each step's base pair is chosen to minimise the nesting of radicals, which is exact
for that criterion because nesting only grows along a plan.

Complexity: O(J² · B^d) eager locations of O(J + L) each, for J joints, d the coupling
degree and B ≤ J the branching of a parameter step; in practice milliseconds per truss
up to 13 links. Reference: thesis §2.6–2.7 and §3.4.1 (plans for 5/B1, 7/B1–B3, 9/B28).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from functools import lru_cache
from itertools import combinations

from baranov.topology import KinematicChain, TopologyError, require_one_dof_chain, require_rigid_chain

from .plan import DistanceKind, Plan, Step, StepKind

Pair = frozenset[int]


@dataclass
class _Tables:
    """Joint-graph tables of one chain, indexed by joint position in the chain."""

    names: list[str]
    joint_links: list[tuple[int, int]]
    link_joints: list[list[int]]
    link_masks: list[int]
    common: list[list[int | None]]
    full: int

    @classmethod
    def of(cls, chain: KinematicChain) -> _Tables:
        names = [joint.name for joint in chain.joints]
        joint_links = [joint.links for joint in chain.joints]
        link_joints: list[list[int]] = [[] for _ in range(chain.number_of_links)]
        for k, (a, b) in enumerate(joint_links):
            link_joints[a].append(k)
            link_joints[b].append(k)
        count = len(names)
        common: list[list[int | None]] = [[None] * count for _ in range(count)]
        for link, joints in enumerate(link_joints):
            for u in joints:
                for v in joints:
                    if u != v:
                        common[u][v] = link
        masks = [sum(1 << k for k in joints) for joints in link_joints]
        return cls(names, joint_links, link_joints, masks, common, (1 << count) - 1)


def _eager_set(tables: _Tables, located: int, cache: dict[int, int]) -> int:
    """The located set reached by eager location (rules 1 and 2) from ``located``."""
    start = located
    if start in cache:
        return cache[start]
    changed = True
    while changed:
        changed = False
        for mask in tables.link_masks:
            inside = located & mask
            if inside != mask and inside & (inside - 1):  # at least two located, not all
                located |= mask
                changed = True
        if changed:
            continue
        for k, (a, b) in enumerate(tables.joint_links):
            if not located >> k & 1 and located & tables.link_masks[a] and located & tables.link_masks[b]:
                located |= 1 << k
                changed = True
    cache[start] = located
    return located


def _parameter_candidates(tables: _Tables, located: int) -> Iterator[int]:
    """Joints that a parameter step can locate: with a located joint on a common link
    (the known distance) and a located joint on no common link (the parameter)."""
    for k in range(len(tables.names)):
        if located >> k & 1:
            continue
        known = unknown = False
        for other in range(len(tables.names)):
            if located >> other & 1:
                if tables.common[k][other] is None:
                    unknown = True
                else:
                    known = True
        if known and unknown:
            yield k


@dataclass(frozen=True)
class _Constraints:
    reference: Pair | None
    parameters: frozenset[Pair] | None

    def allows_reference(self, tables: _Tables, a: int, b: int) -> bool:
        if self.reference is not None and frozenset((a, b)) != self.reference:
            return False
        if self.parameters is not None and tables.common[a][b] is None:
            return frozenset((a, b)) in self.parameters
        return True

    def allows_parameter(self, i: int, k: int) -> bool:
        return self.parameters is None or frozenset((i, k)) in self.parameters


def _reference_pairs(tables: _Tables, constraints: _Constraints) -> list[tuple[int, int]]:
    return [
        (a, b)
        for a, b in combinations(range(len(tables.names)), 2)
        if constraints.allows_reference(tables, a, b)
    ]


def _minimum_parameters(tables: _Tables, constraints: _Constraints, cache: dict[int, int]) -> int | None:
    """Fewest parameters that locate every joint: a search over located sets by cost."""
    buckets: list[set[int]] = [set() for _ in range(len(tables.names) + 2)]
    for a, b in _reference_pairs(tables, constraints):
        cost = 0 if tables.common[a][b] is not None else 1
        buckets[cost].add(_eager_set(tables, (1 << a) | (1 << b), cache))
    seen: set[int] = set()
    for cost in range(len(buckets) - 1):
        bucket = buckets[cost] - seen
        if tables.full in bucket:
            return cost
        seen |= bucket
        for located in bucket:
            for k in _parameter_candidates(tables, located):
                if any(
                    located >> i & 1 and tables.common[i][k] is None and constraints.allows_parameter(i, k)
                    for i in range(len(tables.names))
                ):
                    buckets[cost + 1].add(_eager_set(tables, located | (1 << k), cache))
    return None


class _PartialPlan:
    """A plan under construction: the located joints, their radical depths and the steps.

    Copied at every branch of the search (:meth:`copy`), so branches never share state.
    """

    __slots__ = ("t", "constraints", "order", "rank", "depth", "by_link", "link_located",
                 "steps", "parameters", "enforced", "free")

    def __init__(self, tables: _Tables, constraints: _Constraints, reference: tuple[int, int]):
        a, b = reference
        self.t = tables
        self.constraints = constraints
        self.order: list[int] = []
        self.rank: dict[int, int] = {}
        self.depth: dict[int, int] = {}
        self.by_link: dict[int, int] = {}
        self.link_located: list[list[int]] = [[] for _ in tables.link_joints]
        self.steps: list[Step] = []
        self.parameters: list[Pair] = []
        self.enforced: set[Pair] = set()
        self.free = 0
        self._mark(a, 0)
        self._mark(b, 0)
        if tables.common[a][b] is None:
            self.parameters.append(frozenset((a, b)))
        else:
            self.enforced.add(frozenset((a, b)))

    def copy(self) -> _PartialPlan:
        other = object.__new__(_PartialPlan)
        other.t, other.constraints = self.t, self.constraints
        other.order, other.rank, other.depth = list(self.order), dict(self.rank), dict(self.depth)
        other.by_link = dict(self.by_link)
        other.link_located = [list(x) for x in self.link_located]
        other.steps, other.parameters = list(self.steps), list(self.parameters)
        other.enforced, other.free = set(self.enforced), self.free
        return other

    @property
    def complete(self) -> bool:
        return len(self.order) == len(self.t.names)

    def bound(self, degree: int) -> tuple:
        """A lower bound on the first four components of the final ranking key."""
        return (degree, 0, self.free, tuple(sorted((s.radical_depth for s in self.steps), reverse=True)))

    def _mark(self, k: int, depth: int) -> None:
        self.rank[k] = len(self.order)
        self.order.append(k)
        self.depth[k] = depth
        for link in self.t.joint_links[k]:
            self.link_located[link].append(k)

    def _distance_kind(self, i: int, j: int) -> DistanceKind:
        if self.t.common[i][j] is not None:
            return DistanceKind.KNOWN
        if frozenset((i, j)) in self.parameters:
            return DistanceKind.PARAMETER
        return DistanceKind.COMPUTED

    def _radical(self, i: int, j: int, kind: StepKind, distance: DistanceKind) -> int:
        if kind is StepKind.LINK or (distance is DistanceKind.KNOWN and kind is StepKind.CROSS):
            own = 0
        elif distance is DistanceKind.COMPUTED:
            own = 1 + max(self.depth[i], self.depth[j])
        else:
            own = 1
        return max(self.depth[i], self.depth[j], own)

    def _add(self, k: int, i: int, j: int, kind: StepKind, link: int | None) -> None:
        distance = self._distance_kind(i, j)
        depth = self._radical(i, j, kind, distance)
        names = self.t.names
        self.steps.append(Step(names[k], (names[i], names[j]), kind, link, distance, depth))
        if kind is not StepKind.LINK:
            self.free += 1
        else:
            self.by_link[k] = link
        self._mark(k, depth)

    def eager(self, limit: tuple[int, int] | None = None) -> bool:
        """Apply link steps, then one cross step at a time, until neither applies.

        With ``limit = (free, depth)``, stop early and return False as soon as the plan
        has more free signs than ``free``, or as many and a step deeper than ``depth``.
        """
        t = self.t
        while True:
            if limit is not None and self.steps and (
                self.free > limit[0] or (self.free == limit[0] and self.steps[-1].radical_depth > limit[1])
            ):
                return False
            progress = False
            for link, joints in enumerate(t.link_joints):
                located = self.link_located[link]
                if 2 <= len(located) < len(joints):
                    u, v = min(combinations(located, 2),
                               key=lambda p: (max(self.depth[p[0]], self.depth[p[1]]), self.rank[p[1]]))
                    for x in joints:
                        if x not in self.depth:
                            self._add(x, u, v, StepKind.LINK, link)
                            self.enforced.update((frozenset((u, x)), frozenset((v, x))))
                    progress = True
            if progress:
                continue
            best = None
            for k, (la, lb) in enumerate(t.joint_links):
                if k in self.depth or not self.link_located[la] or not self.link_located[lb]:
                    continue
                # The base joint on the link still to be built comes first: its link step
                # then uses M_k - M_i = Z_{i,j,k}(M_j - M_i), a single product (thesis 2.24).
                rest_a = len(t.link_joints[la]) - len(self.link_located[la])
                rest_b = len(t.link_joints[lb]) - len(self.link_located[lb])
                for i in self.link_located[la]:
                    for j in self.link_located[lb]:
                        i2, j2 = (j, i) if (rest_b, -j) > (rest_a, -i) else (i, j)
                        depth = self._radical(i2, j2, StepKind.CROSS, self._distance_kind(i2, j2))
                        if best is None or (depth, k, i2, j2) < best:
                            best = (depth, k, i2, j2)
            if best is None:
                return True
            _, k, i, j = best
            self._add(k, i, j, StepKind.CROSS, None)
            self.enforced.update((frozenset((i, k)), frozenset((j, k))))

    def parameter_step(self, k: int) -> bool:
        """Locate ``k`` through a new parameter s_{i,k}; False if no allowed pair exists."""
        t = self.t
        options = []
        for j in self.order:
            if t.common[j][k] is None:
                continue
            for i in self.order:
                if t.common[i][k] is None and self.constraints.allows_parameter(i, k):
                    depth = self._radical(i, j, StepKind.PARAMETER, self._distance_kind(i, j))
                    options.append((depth, self.rank[i], self.rank[j], i, j))
        if not options:
            return False
        *_, i, j = min(options)
        self.parameters.append(frozenset((i, k)))
        self._add(k, i, j, StepKind.PARAMETER, None)
        self.enforced.add(frozenset((j, k)))
        return True

    def finish(self, reference: tuple[int, int]) -> Plan:
        """The complete plan, with its closure conditions and orientation checks."""
        t, names = self.t, self.t.names
        closures: list[tuple[int, int]] = []
        checks: list[tuple[str, str, str]] = []
        for link, joints in enumerate(t.link_joints):
            located = sorted(joints, key=self.rank.__getitem__)
            w1, w2 = located[0], located[1]
            if frozenset((w1, w2)) not in self.enforced:
                closures.append((w1, w2))
            for x in located[2:]:
                if self.by_link.get(x) == link:
                    continue
                closures += [(w, x) for w in (w1, w2) if frozenset((w, x)) not in self.enforced]
                checks.append((names[w1], names[w2], names[x]))
        closures.sort(key=lambda p: (self.rank[p[1]], self.rank[p[0]]))

        def pair_names(pair) -> tuple[str, str]:
            u, v = sorted(pair, key=self.rank.__getitem__)
            return names[u], names[v]

        return Plan(
            reference=(names[reference[0]], names[reference[1]]),
            parameters=tuple(pair_names(p) for p in self.parameters),
            steps=tuple(self.steps),
            closure_pairs=tuple((names[u], names[v]) for u, v in closures),
            orientation_checks=tuple(checks),
        )


def _branch_and_bound(tables: _Tables, constraints: _Constraints, degree: int, count: int) -> list[Plan]:
    """The ``count`` best plans with ``degree`` parameters, by exhaustive search over
    reference pairs and parameter steps, pruned by :meth:`_PartialPlan.bound`."""
    best: list[tuple[tuple, Plan]] = []

    def visit(state: _PartialPlan, reference: tuple[int, int]) -> None:
        limit = None
        if len(best) == count and best[-1][0][1] == 0:  # incumbent without extra conditions
            worst = best[-1][0]
            limit = (worst[2], worst[3][0] if worst[3] else 0)
        if not state.eager(limit):
            return
        if len(best) == count:
            bound, worst = state.bound(degree), best[-1][0]
            # References are visited in the ranking key's order, so once the k-th best has
            # a smaller reference, merely equal quality already ranks this plan lower.
            if bound > worst[:4] or (bound == worst[:4] and worst[4] < names_of(reference)):
                return
        if state.complete:
            if len(state.parameters) == degree:
                plan = state.finish(reference)
                key = plan.ranking_key()
                if all(key != k for k, _ in best):
                    best.append((key, plan))
                    best.sort(key=lambda item: item[0])
                    del best[count:]
            return
        if len(state.parameters) >= degree:
            return
        located = sum(1 << k for k in state.order)
        for k in _parameter_candidates(tables, located):
            child = state.copy()
            if child.parameter_step(k):
                visit(child, reference)

    def names_of(pair: tuple[int, int]) -> tuple[str, str]:
        return tables.names[pair[0]], tables.names[pair[1]]

    for a, b in sorted(_reference_pairs(tables, constraints), key=names_of):
        visit(_PartialPlan(tables, constraints, (a, b)), (a, b))
    return [plan for _, plan in best]


def _constraints(chain: KinematicChain, reference, parameters) -> _Constraints:
    index = {joint.name: k for k, joint in enumerate(chain.joints)}

    def pair(value, what: str) -> Pair:
        try:
            u, v = value
        except (TypeError, ValueError):
            raise ValueError(f"{what} {value!r}: expected a pair of joint names") from None
        for name in (u, v):
            if name not in index:
                raise TopologyError(f"joint {name}: no such joint in this chain ({what})")
        if u == v:
            raise ValueError(f"{what} {value!r}: the two joints must differ")
        return frozenset((index[u], index[v]))

    return _Constraints(
        pair(reference, "reference") if reference is not None else None,
        frozenset(pair(p, "parameter") for p in parameters) if parameters is not None else None,
    )


def coupling_degree(chain: KinematicChain) -> int:
    """The fewest parameters (unknown squared distances) of any bilateration plan.

    Thesis ch. 3: 0 for the triad, 1 for the pentad and the three 7-link trusses;
    for 9 links, 24 trusses have 1 and four (9/B25–B28) have 2.

    >>> from baranov.topology import chain_from_link_graph
    >>> coupling_degree(chain_from_link_graph([(0, 2), (0, 3), (0, 4), (1, 2), (1, 3), (1, 4)]))
    1
    """
    tables = _Tables.of(_checked(chain))
    degree = _minimum_parameters(tables, _Constraints(None, None), {})
    if degree is None:  # cannot happen for a rigid chain: every joint is eventually reachable
        raise TopologyError("no bilateration plan locates every joint")
    return degree


def parametrising_distances(chain: KinematicChain) -> int:
    """The fewest squared distances that parametrise the configuration space of a
    one-degree-of-freedom chain (mobility 1): the parameters of its best plans, which
    locate every joint from them with one closure condition fewer than parameters
    (thesis §6.4, Table 6.2: 1 for the four-bar, the Watt and Stephenson six-bars and 12
    of the 16 eight-bar Grübler chains, 2 for the other four, the double butterfly
    among them). Same search as :func:`coupling_degree`.

    >>> from baranov.topology import chain_from_link_graph
    >>> parametrising_distances(chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0)]))  # four-bar
    1
    """
    require_one_dof_chain(chain)
    degree = _minimum_parameters(_Tables.of(chain), _Constraints(None, None), {})
    if degree is None:
        raise TopologyError("no bilateration plan locates every joint")
    return degree


def one_dof_plans(chain: KinematicChain, count: int = 1, reference: tuple[str, str] | None = None,
                  parameters: Iterable[tuple[str, str]] | None = None) -> list[Plan]:
    """The ``count`` best plans of a one-degree-of-freedom chain, as
    :func:`bilateration_plans` for a rigid one: d parameters (:func:`parametrising_distances`)
    and d − 1 closure conditions; its configuration space is a curve in the space of the
    d parameters, split into pieces by the signs of the free-sign triangles (thesis §6.3).

    >>> from baranov.topology import chain_from_link_graph
    >>> plan = one_dof_plans(chain_from_link_graph([(0, 1), (1, 2), (2, 3), (3, 0)]))[0]
    >>> len(plan.parameters), len(plan.closure_pairs)
    (1, 0)
    """
    require_one_dof_chain(chain)
    return _ranked_plans(chain, count, reference, parameters)


def bilateration_plans(
    chain: KinematicChain,
    count: int = 1,
    reference: tuple[str, str] | None = None,
    parameters: Iterable[tuple[str, str]] | None = None,
    extra_parameters: int = 0,
) -> list[Plan]:
    """The ``count`` best plans with the fewest parameters (``extra_parameters`` more than
    the fewest, if given), best first.

    Parameters
    ----------
    chain
        a rigid chain (mobility 0, no over-constrained sub-chain).
    count
        how many plans to return (fewer if fewer exist).
    reference
        fix the reference pair, e.g. ``("P1", "P6")``.
    parameters
        allow only these joint pairs as parameters (the reference pair
        included when it is not a link dimension), e.g. ``[("P1", "P6")]`` for the
        thesis's formulation of 5/B1. The minimum is then taken over such plans.
    extra_parameters
        plans with this many parameters more than the fewest: where no plan of the
        fewest suits a constraint the search does not know (slider joints,
        :func:`~baranov.planner.sliders.slider_plan`), one more parameter gives the
        search room (3020 of the 3095 nine-link slider chains that no plan of their
        coupling degree suited have one with one parameter more).

    Raises :class:`~baranov.topology.TopologyError` for a chain that is not rigid or is
    over-constrained, or naming a constraint no plan can meet.

    >>> from baranov.literature.trusses import thesis_truss
    >>> pentad = thesis_truss("5/B1").chain()
    >>> plan = bilateration_plans(pentad, reference=("P1", "P6"))[0]
    >>> print(plan.describe())
    reference pair P1, P6
    parameters s1,6
    P3: Z1,6,3 (free sign)
    P2: Z1,3,2 (link L0, fixed sign)
    P4: Z6,1,4 (free sign)
    P5: Z6,4,5 (link L1, fixed sign)
    closure s2,5
    """
    return _ranked_plans(_checked(chain), count, reference, parameters, extra_parameters)


#: How many (chain, count, constraints) searches the plan cache keeps: a solve of a
#: topology it has met does no graph search (issue 21: on 7/B1 the search was about 10 ms
#: of a 70 ms numeric solve, repeated on every call; a batch of one topology pays it once).
PLAN_CACHE_SIZE = 1024


def _ranked_plans(chain: KinematicChain, count: int, reference, parameters, extra_parameters: int = 0) -> list[Plan]:
    """:func:`_searched_plans`, cached on the exact chain (its joint and link names
    included: a relabelled chain is searched again) and the constraints. Plans are frozen,
    so the cached ones are shared; the list is the caller's."""
    if reference is not None:
        reference = tuple(reference) if isinstance(reference, list) else reference
    if parameters is not None:
        parameters = tuple(tuple(p) if isinstance(p, list) else p for p in parameters)
    try:
        return list(_cached_plans(chain, count, reference, parameters, extra_parameters))
    except TypeError:  # an unhashable constraint: searched, and refused there if malformed
        return list(_searched_plans(chain, count, reference, parameters, extra_parameters))


def clear_plan_cache() -> None:
    """Forget every cached plan search (benchmarks of a topology's first solve; tests)."""
    _cached_plans.cache_clear()
    _checked.cache_clear()


@lru_cache(maxsize=PLAN_CACHE_SIZE)
def _cached_plans(chain: KinematicChain, count: int, reference, parameters, extra_parameters: int) -> tuple[Plan, ...]:
    return _searched_plans(chain, count, reference, parameters, extra_parameters)


def _searched_plans(chain: KinematicChain, count: int, reference, parameters,
                    extra_parameters: int = 0) -> tuple[Plan, ...]:
    if count < 1:
        raise ValueError(f"count={count}: ask for at least one plan")
    if extra_parameters < 0:
        raise ValueError(f"extra_parameters={extra_parameters}: 0 or more")
    constraints = _constraints(chain, reference, parameters)
    tables = _Tables.of(chain)
    cache: dict[int, int] = {}
    degree = _minimum_parameters(tables, constraints, cache)
    if degree is None:
        raise TopologyError("no bilateration plan meets the given reference/parameter constraints")
    ranked = _branch_and_bound(tables, constraints, degree + extra_parameters, count)
    if not ranked:
        raise TopologyError("no bilateration plan meets the given reference/parameter constraints")
    return tuple(ranked)


def best_plan(chain: KinematicChain) -> Plan:
    """The best plan (see :meth:`~baranov.planner.plan.Plan.ranking_key`)."""
    return bilateration_plans(chain, 1)[0]


#: How many of the best plans :func:`plan_avoiding` searches.
ALTERNATIVE_PLANS = 50


def plans_avoiding(chain: KinematicChain, pairs: Iterable[frozenset[str]],
                   count: int = ALTERNATIVE_PLANS) -> Iterator[Plan]:
    """The plans, among the ``count`` best and best first, with none of the joint pairs
    ``pairs`` as their reference or as the base of a step. A bilateration Z_{i,j,k}
    divides by s_{i,j} (thesis eq. 2.7): where P_i = P_j it is undefined, so joints that
    coincide must never be a base (thesis §5.1.3.2–5.1.3.3).

    Cost: that of :func:`bilateration_plans` with ``count`` plans.

    >>> from baranov.literature.trusses import thesis_truss
    >>> pentad = thesis_truss("5/B1").chain()
    >>> first = next(plans_avoiding(pentad, [frozenset(best_plan(pentad).reference)]))
    >>> first.reference != best_plan(pentad).reference
    True
    """
    pairs = set(pairs)
    for plan in bilateration_plans(chain, count):
        if not pairs & ({frozenset(plan.reference)} | {frozenset(step.base) for step in plan.steps}):
            yield plan


def plan_avoiding(chain: KinematicChain, pairs: Iterable[frozenset[str]], count: int = ALTERNATIVE_PLANS) -> Plan | None:
    """The best plan that :func:`plans_avoiding` yields, None if there is none; the best
    plan itself (no search of ``count`` plans) when ``pairs`` is empty."""
    pairs = set(pairs)
    if not pairs:
        return best_plan(chain)
    return next(plans_avoiding(chain, pairs, count), None)


@lru_cache(maxsize=PLAN_CACHE_SIZE)
def _checked(chain: KinematicChain) -> KinematicChain:
    """``chain``, checked rigid once (cached like the plans: a solve of a topology met
    before repeats no check; a chain that fails raises every time)."""
    require_rigid_chain(chain)
    return chain
