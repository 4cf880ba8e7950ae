"""The live explorer (``baranov explore``): every assembly mode of a scene or robot
redrawn while its dimensions are dragged, in a local web page.

* :mod:`~baranov.explore.document` — the dimensions a page varies (controls) and the
  linkage they make;
* :mod:`~baranov.explore.continuity` — modes followed from one redraw to the next, and
  where their number changes;
* :mod:`~baranov.explore.frames` — one redraw, and a dimension's profile;
* :mod:`~baranov.explore.server` — the local HTTP server and the page's JSON API.
"""

from .continuity import count_changes, match_modes
from .document import Control, ControlError, Document, document_data, document_scene, load_document
from .frames import dimension_profile, solve_frame
from .server import ExplorerServer, serve

__all__ = ["Control", "ControlError", "Document", "ExplorerServer", "count_changes", "dimension_profile",
           "document_data", "document_scene", "load_document", "match_modes", "serve", "solve_frame"]
