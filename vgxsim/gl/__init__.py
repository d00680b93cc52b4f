"""The IRIS GL namespace: ``from vgxsim.gl import *`` gives every function and,
for convenience, every gl.h constant, as in C where gl.h declares both.

Functions are grouped by manual section in the private modules below; each call
validates its arguments and raises a :class:`GLError` subclass naming the call.
"""

from vgxsim.GL import *  # noqa: F401,F403  (constants, for convenience)

from ._accum import *  # noqa: F401,F403
from ._clip import *  # noqa: F401,F403
from ._color import *  # noqa: F401,F403
from ._compat import *  # noqa: F401,F403
from ._core import GLError, GLTypeError, GLUsageError, GLValueError  # noqa: F401
from ._curves import *  # noqa: F401,F403
from ._depthcue import *  # noqa: F401,F403
from ._draw import *  # noqa: F401,F403
from ._drawmode import *  # noqa: F401,F403
from ._events import *  # noqa: F401,F403
from ._fm import *  # noqa: F401,F403
from ._fog import *  # noqa: F401,F403
from ._lighting import *  # noqa: F401,F403
from ._matrix import *  # noqa: F401,F403
from ._menus import *  # noqa: F401,F403
from ._nurbs import *  # noqa: F401,F403
from ._objects import *  # noqa: F401,F403
from ._oldstyle import *  # noqa: F401,F403
from ._pick import *  # noqa: F401,F403
from ._query import *  # noqa: F401,F403
from ._raster import *  # noqa: F401,F403
from ._readback import *  # noqa: F401,F403
from ._screens import *  # noqa: F401,F403
from ._text import *  # noqa: F401,F403
from ._texture import *  # noqa: F401,F403
from ._window import *  # noqa: F401,F403
