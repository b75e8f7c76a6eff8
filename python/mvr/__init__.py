"""mvr for Python: render glTF scenes into many views at once, headless, into
numpy arrays. A thin ctypes layer over libmvr.so (no compiled extension);
numpy is its one dependency.

    import mvr
    with mvr.Context() as ctx, mvr.Scene.load("model.gltf") as scene, \\
            mvr.Views.layout(scene, "ring", count=8, aspect=4 / 3) as views:
        for v in ctx.render(scene, views, (640, 480), outputs=("color", "depth", "ids")):
            v.color      # (480, 640, 4) uint8, row 0 at the top
            v.camera.K   # 3x3 intrinsics (OpenCV), v.camera.camera_to_world (OpenGL camera)

ctx.render(scene) alone renders what `mvr render model.gltf` writes, byte for
byte: the same views, size, environment, clear colour, exposure and tone map
(DEFAULT_SIZE, DEFAULT_CLEAR_COLOR, DEFAULT_ENVIRONMENT; docs/guide.md, Python,
"Defaults").

Failed calls raise mvr.Error with mvr's own message. docs/guide.md ("Python")
says where the package finds libmvr.so (MVR_LIBRARY_DIR, the installed
package's folder, the source tree's build/) and what every output holds.
"""
from ._common import ClosedError, Error
from ._lib import LIBRARY_DIR
from .context import DEFAULT_CLEAR_COLOR, DEFAULT_ENVIRONMENT, DEFAULT_SIZE, OUTPUTS, Context, RenderedView
from .scene import Environment, Scene
from .views import Camera, Views, look_at

__all__ = ["Camera", "ClosedError", "Context", "DEFAULT_CLEAR_COLOR", "DEFAULT_ENVIRONMENT", "DEFAULT_SIZE",
           "Environment", "Error", "LIBRARY_DIR", "OUTPUTS", "RenderedView", "Scene", "Views", "look_at"]
__version__ = "0.1.0"
