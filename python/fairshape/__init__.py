"""fairshape: variational multiresolution shape design from Python.

Meshes are NumPy arrays (V: n×3 float64, F: m×k int array or a list of vertex-id lists);
sparse matrices are scipy.sparse.csr_matrix; errors are fairshape.Error and its subclasses
carrying fairshape's own message. The compiled half is fairshape._fairshape; what copies and
what does not is said in each docstring (and in README.md, "Python").
"""

from ._fairshape import (  # noqa: F401  (the public API)
    __version__,
    Error, InvalidInput, InvalidIndex, InvalidConfig, TopologyError, SolverError, FileError, MissingFileError, ParseError, OutputError,
    Mesh, read_mesh, write_mesh, read_arrays,
    MultiresSurface, remesh, subdivide, limit_positions, limit_normals, limit_matrix, relative_detail_change,
    stretch_bend_hessian, energy_hessian, components, constraint_modes,
    curve_components, curve_max_levels, Sheet, qp_solvers,
    SheetSession, SheetStep, SheetSolve, SheetConstraintCheck, SheetConfigStep, FreeCurveStep,
)
from ._summary import Summary, SolveFailed, RunFailed  # noqa: F401
from ._constraints import constraint, fixed, position, energy  # noqa: F401
from ._edit import edit, EditResult, SessionStep, SurfaceEditSession  # noqa: F401
from ._solve import solve  # noqa: F401
from ._run import run  # noqa: F401
from ._curves import Curve, CurveEditResult, CurveSession, CurveStep, edit_curve  # noqa: F401
from ._sheets import SheetResult, design_sheet  # noqa: F401
from ._features import FeatureResult, FeatureSession, feature, apply_features  # noqa: F401
