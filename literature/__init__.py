"""Data from the literature, in one place: the thesis's trusses with its joint numbering
and their identification in the catalog (:mod:`.trusses`), the closure conditions and
assembly-mode counts of its Appendix A (:mod:`.appendix_a`), and the published counts of
Table 3.1 (:mod:`.counts`)."""

from .appendix_a import APPENDIX_A_CONDITIONS, appendix_a_conditions, appendix_a_labelling
from .counts import DISCREPANCY_NOTE, LITERATURE, LITERATURE_COUPLING
from .trusses import APPENDIX_A_ASSEMBLY_MODES, THESIS_TRUSSES, PublishedTruss, thesis_name, thesis_truss

__all__ = [
    "APPENDIX_A_ASSEMBLY_MODES",
    "APPENDIX_A_CONDITIONS",
    "DISCREPANCY_NOTE",
    "LITERATURE",
    "LITERATURE_COUPLING",
    "PublishedTruss",
    "THESIS_TRUSSES",
    "appendix_a_conditions",
    "appendix_a_labelling",
    "thesis_name",
    "thesis_truss",
]
