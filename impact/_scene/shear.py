"""The `shear` section of an indentation scene: a quasi-static tangential program at the held
normal load (Cattaneo–Mindlin loading, Mindlin–Deresiewicz unloading and reloading)."""

from typing import TYPE_CHECKING, Annotated, Literal

from pydantic import Field, field_validator

from .domains import Domain, within
from .errors import FieldProblem
from .profiles import Number
from .sections import Section

if TYPE_CHECKING:
    from .scene import Scene

SHIFT = Domain(-1e6, 1e6, "m or N", reason="a shift of at most a kilometre or a force of at most a meganewton")
SAMPLES = Domain(2, 100_000, "", reason="each leg's points are computed at once")
MOST_LEGS = 16
MAX_SPRINGS = 1_000_000  # each point of the program costs O(N)


class Shear(Section):
    """A tangential program at the normal load of `program.peak`, held: from rest through the
    turning points of `path` (displacements or forces), each leg monotone."""

    control: Literal["displacement", "force"] = Field(
        description="what the program drives: the tangential 'displacement' (m) or 'force' (N)"
    )
    path: list[Annotated[Number, within(SHIFT)]] = Field(
        description=(
            "the turning points of the program, from rest (m or N): e.g. [δ, −δ, δ] loads, unloads and reloads; "
            "under force control each |Q| below μF_n (the contact would slide)"
        ),
        min_length=1,
        max_length=MOST_LEGS,
    )
    samples: Annotated[int, within(SAMPLES)] = Field(101, description="points of each leg")

    @field_validator("path")
    @classmethod
    def _legs_move(cls, path: list[float]) -> list[float]:
        for index, (start, end) in enumerate(zip([0.0, *path], path, strict=False)):
            if start == end:
                raise ValueError(f"turning point {index} ({end:g}) repeats the point before it: a leg must move")
        return path

    def check(self, scene: "Scene") -> None:
        """Refuse (`FieldProblem`, relative to the scene) what a shear test cannot run."""
        friction = scene.effects.friction
        why = None
        if scene.kind != "indentation":
            why = "only for kind 'indentation': an impact's tangential motion follows from initial.angle and spin"
        elif friction is None:
            why = "needs effects.friction (the coefficient μ of the tangential springs)"
        elif scene.contact.springs == "continuum":
            why = "runs on a spring array (contact.springs: N): the tangential state is one displacement per spring"
        elif scene.contact.springs > MAX_SPRINGS:
            why = f"takes at most {MAX_SPRINGS} springs, not {scene.contact.springs}: each point costs O(N)"
        elif scene.loading.cycles != 1 or scene.loading.unload_to is not None:
            why = "holds the normal load at program.peak: give one cycle and no unload_to"
        elif scene.active_adhesion is not None:
            why = (
                "holds a normal contact without adhesion (the springs pressed by the load from the tip, the "
                "state of the closed forms); with adhesion run an oblique impact"
            )
        if why is not None:
            raise FieldProblem("shear", why)
        if self.control == "force":
            self._check_forces(scene)

    def _check_forces(self, scene: "Scene") -> None:
        """A force program needs a force-held normal load and forces below μF_n."""
        friction = scene.effects.friction
        assert friction is not None, "checked: a shear test names friction"
        if scene.control != "force":
            raise FieldProblem(
                "shear.control",
                "'force' needs the normal load held as a force (control: force): the limit μF_n must be known",
            )
        most = friction.coefficient * scene.loading.peak
        largest = max(abs(value) for value in self.path)
        if largest >= most:
            raise FieldProblem(
                "shear.path",
                f"|Q| = {largest:g} N reaches μF_n = {most:g} N: the whole contact would slide and no "
                "displacement holds that force",
            )
