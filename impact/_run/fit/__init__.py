"""Calibration: fit scene values to measurements by weighted least squares (issue #15)."""

from .models import Model as Model
from .models import theory_applies as theory_applies
from .models import theory_model as theory_model
from .solve import FitResult as FitResult
from .solve import fit as fit
from .solve import fit_spec as fit_spec
