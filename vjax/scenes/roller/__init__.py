"""The needle roller bearing (thesis Chapter 2): rollers between two viscoelastic rings, the
load shared by a force balance over the contacts (:mod:`.balance`), the rollers' positions
and interferences (:mod:`.geometry`), the scene and its result (:mod:`.scene`)."""
from .scene import RollerOptions, RollerResult, roller_bearing, roller_patch_speeds

__all__ = ["RollerOptions", "RollerResult", "roller_bearing", "roller_patch_speeds"]
