"""Published counts of trusses, Assur groups, slider chains and coupling degrees, and
where this project's verified counts differ from them (the project's rule of "honesty about the
literature": both are kept, the verified value tested, the published one cited)."""

#: Literature values (thesis Table 3.1 after Yang & Yao 1994; slider chains: thesis ch. 4).
LITERATURE = {
    3: {"trusses": 1, "assur_groups": 1, "slider_chains": 3},
    5: {"trusses": 1, "assur_groups": 2, "slider_chains": 10},
    7: {"trusses": 3, "assur_groups": 10, "slider_chains": None},
    9: {"trusses": 28, "assur_groups": 173, "slider_chains": None},
    11: {"trusses": 239, "assur_groups": 5442, "slider_chains": None},
    13: {"trusses": None, "assur_groups": 251638, "slider_chains": None},
}

#: Coupling-degree distribution, thesis Table 3.1 (after Yang & Yao 1994).
LITERATURE_COUPLING = {3: {0: 1}, 5: {1: 1}, 7: {1: 3}, 9: {1: 24, 2: 4}, 11: {1: 197, 2: 42}}

#: Assembly modes of the ten fully-parallel planar robot families I–X, whose locked
#: structures are the ten slider chains of the pentad (thesis §5.2, Table 5.3; the AM
#: column of Tables 5.4–5.6).
ROBOT_FAMILY_ASSEMBLY_MODES = {"I": 6, "II": 6, "III": 6, "IV": 4, "V": 4, "VI": 2, "VII": 2, "VIII": 2, "IX": 1,
                               "X": 1}

#: Why the 11-link counts differ from the thesis's Table 3.1 (catalog/summary.md).
DISCREPANCY_NOTE = [
    "The thesis's Table 3.1 gives, for 11 links, 239 trusses (Yang & Yao 1994, topologies never",
    "published) and 5442 Assur groups. These two numbers contradict each other: removing one",
    "link of an 11-link truss gives at most 11 different Assur groups, so 239 trusses give at",
    "most 2629. Both enumerations here (the library's generator and the brute-force filter over",
    "every connected 11-link graph with 15 joints and no link with fewer than two joints) find the",
    "same 562 trusses, which give 5438 Assur groups: within 4 of the published 5442, and far from",
    "what 239 trusses allow. At 13 links the same computation gives 251638 Assur groups, exactly",
    "the published value. We therefore take 239 to be wrong. We could not find the cause of the",
    "4-group difference at 11 links; 5438 was confirmed a second way, by counting",
    "non-isomorphic (truss, removed link) pairs with vertex-coloured nauty certificates",
    "(`tests/test_enumeration.py`). See `docs/enumeration.md`.",
    "",
    "Coupling degrees agree with Yang & Yao for 3-9 links. For 11 links the published split",
    "197 + 42 covers the 239 trusses above; over the 562 found here it is 409 + 153 (no truss",
    "needs 3 parameters). See `docs/planner.md`.",
]
