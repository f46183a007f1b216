"""bounce from Python: real-time global-illumination techniques side by side, measured against ground truth.

The same library the ``bounce`` command line calls, with numpy arrays instead of files::

    import bounce
    scene = bounce.Scene.load("cornell-box")
    with bounce.Renderer(scene, "rsm", 128, settings={"vplGrid": 16}, component="indirect") as r:
        image, record = r.frame(0)   # float32 H x W x 3 linear radiance, and the run record
    ref = bounce.reference(scene, 128, spp=256, **bounce.reference_scope("rsm"))
    print(bounce.compare(image, ref, metrics=["relRms", "flipLdr"]))

Rendering needs an OpenGL 4.5 context; the module makes one headless context (EGL, as the CLI) the
first time it is needed and keeps it. Every GL call runs on one thread of the module; the GIL is
released while rendering, path tracing, comparing and sweeping. Bad input raises ``bounce.Error``
with the command line's one-line message. docs/python.md documents the API with an example.
"""
from __future__ import annotations

import json as _json
import os as _os
from typing import Any, Iterable, Mapping, Optional, Sequence, Tuple, Union

import numpy as _np

from . import _bounce

__all__ = [
    "Error", "scenes", "techniques", "technique", "renderer_settings", "reference_scope", "Scene", "Renderer",
    "CameraPath", "Reference", "PhotonMap", "reference", "photon_map", "compare", "METRICS", "sweep", "report",
    "gl_info", "select_gpu", "resources", "set_log_level", "read_image", "write_image", "flicker",
]

#: Raised for bad input (unknown technique or setting, bad scene file, out-of-range values, ...) with
#: the one-line message the ``bounce`` command prints for the same input.
Error = _bounce.Error

#: The metric names ``compare`` accepts in ``metrics=[...]`` (docs/metrics.md defines them).
METRICS = ("relMse", "relRms", "mse", "rmse", "mae", "nrmse", "psnr", "ssim", "flipLdr", "flipHdr", "rmsSum8",
           "energy", "testMean", "referenceMean", "heatmap")

Size = Union[int, Tuple[int, int], str]
Vec3 = Sequence[float]


def _size(size: Size) -> str:
    """'WxH' from 64, (64, 48) or '64x48' (the command line's --size, checked there)."""
    if isinstance(size, str):
        return size
    if isinstance(size, (int, _np.integer)) and not isinstance(size, bool):
        return f"{int(size)}x{int(size)}"
    try:
        w, h = size  # type: ignore[misc]
    except (TypeError, ValueError):
        raise Error(f"size {size!r}: give an int, a (width, height) pair or 'WIDTHxHEIGHT'") from None
    return f"{w}x{h}"


def _value(v: Any) -> str:
    """A setting or scene-parameter value as the command line's text (True -> 'true')."""
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


def _bounces(b: Union[int, str]) -> str:
    return str(b)


def scenes() -> list:
    """The built-in scenes: ``[{"name", "description", "params": {name: "default: doc"}}, ...]`` (``bounce list --scenes``)."""
    return _json.loads(_bounce.scenes())


def techniques() -> list:
    """Every registered technique (``bounce list --techniques``).

    Each entry: ``name``, ``summary``, ``paper``, ``scope`` (the reference it is measured against:
    ``bounces`` (int or ``"unbounded"``), ``indirect_only``, ``diffuse_only`` and the compared
    ``component``) and ``settings``: a list of ``{"name", "type", "default", "range", "doc",
    "profile_defaults"}`` from the one declaration that drives ``--set``, the run record and the
    viewer. ``default`` is the llvmpipe profile's; a setting whose default depends on the device
    profile says so in ``profile_defaults`` (``"llvmpipe 32768, gpu 1024"``, else empty): a renderer
    starts from the defaults of its context's profile (core/DeviceProfile.h, docs/gpu.md).
    """
    return _json.loads(_bounce.techniques())


def technique(name: str) -> dict:
    """The entry of :func:`techniques` named ``name`` (``bounce.Error`` listing the known ones otherwise)."""
    entries = techniques()
    for t in entries:
        if t["name"] == name:
            return t
    raise Error(f"unknown technique '{name}' (known: {', '.join(t['name'] for t in entries)})")


def renderer_settings() -> list:
    """The shared renderer settings (``renderer.NAME``), described as a technique's settings are."""
    return _json.loads(_bounce.renderer_settings())


def reference_scope(technique_name: str) -> dict:
    """Keyword arguments of :func:`reference` for the scope ``technique_name`` is measured against.

    ``bounce.reference(scene, 64, 256, **bounce.reference_scope("isr"))``; compare it with the
    technique's ``technique(name)["scope"]["component"]`` output.
    """
    s = technique(technique_name)["scope"]
    return {"bounces": s["bounces"], "indirect_only": s["indirect_only"], "diffuse_only": s["diffuse_only"]}


class Scene:
    """A scene: a built-in one or a scene/model file, with its parameters.

    Renderers made from a scene share it: lights, animated objects and the camera moved here show in
    their next frame, and :func:`reference` renders the scene as it is now. ``copy()`` gives an
    independent scene. The moves are the viewer's (arrow keys, ctrl-drag, its panel) and the camera
    paths' (scene/SceneEdits.h).
    """

    def __init__(self, core: "_bounce.Scene"):
        self._core = core

    @staticmethod
    def load(path_or_builtin: str, **scene_params: Any) -> "Scene":
        """Loads a built-in scene by name (:func:`scenes`) or a file (.json, .gltf, .glb, .obj, .ply).

        ``scene_params`` are the built-in scene's parameters (``bounce render --scene-param``), e.g.
        ``Scene.load("atrium", triangles=20000)``.
        """
        return Scene(_bounce.Scene.load(_os.fspath(path_or_builtin), {k: _value(v) for k, v in scene_params.items()}))

    def copy(self) -> "Scene":
        """An independent copy of the scene as it is now (edits included)."""
        return Scene(self._core.copy())

    def _info(self) -> dict:
        return self._core.info()

    @property
    def name(self) -> str:
        """The scene's name."""
        return self._info()["name"]

    @property
    def source(self) -> str:
        """Where it came from: a file path or ``builtin:NAME``."""
        return self._info()["source"]

    @property
    def params(self) -> dict:
        """The parameters it was loaded with."""
        return dict(self._core.params)

    @property
    def frame_rate(self) -> float:
        """Frames per second: frame ``n`` shows time ``n / frame_rate``."""
        return self._info()["frame_rate"]

    @property
    def lights(self) -> list:
        """``[{"name", "type", "position", "direction", "animated"}, ...]`` (base poses, before animation)."""
        return self._info()["lights"]

    @property
    def objects(self) -> list:
        """``[{"name", "animated"}, ...]``; only animated objects can be moved."""
        return self._info()["objects"]

    @property
    def camera(self) -> dict:
        """The camera's pose ``{"position", "target", "up", "fov"}`` (fov: vertical, radians)."""
        return self._info()["camera"]

    @property
    def triangles(self) -> int:
        """Triangle count."""
        return self._info()["triangles"]

    def time_of_frame(self, frame: int) -> float:
        """Seconds shown by ``frame`` (frame / frame_rate)."""
        return frame / self.frame_rate

    def _index(self, which: Union[int, str], kind: str) -> int:
        if isinstance(which, (int, _np.integer)) and not isinstance(which, bool):
            return int(which)
        items = self.lights if kind == "light" else self.objects
        for i, item in enumerate(items):
            if item["name"] == which:
                return i
        raise Error(f"{kind} '{which}' is not in scene '{self.name}' (known: {', '.join(x['name'] for x in items)})")

    def move_light(self, light: Union[int, str], delta: Vec3) -> None:
        """Moves a light's position by ``delta`` metres (the viewer's arrow keys)."""
        self._core.move_light(self._index(light, "light"), list(delta))

    def set_light(self, light: Union[int, str], position: Optional[Vec3] = None, direction: Optional[Vec3] = None) -> None:
        """Sets a light's position and/or direction, as a camera path's recorded lights do.

        The direction is normalised and must not be zero. A light with an animation track keeps it:
        its pose at time t is the track applied to this base pose.
        """
        i = self._index(light, "light")
        current = self.lights[i] if 0 <= i < len(self.lights) else None
        if current is None:
            raise Error(f"light {i} is not in scene '{self.name}' ({len(self.lights)} lights)")
        self._core.set_light(current["name"], list(position if position is not None else current["position"]),
                             list(direction if direction is not None else current["direction"]))

    def move_object(self, obj: Union[int, str], delta: Vec3) -> None:
        """Moves an animated object by ``delta`` metres (the viewer's ctrl-drag); static geometry cannot move."""
        self._core.move_object(self._index(obj, "object"), list(delta))

    def set_camera(self, position: Vec3, target: Vec3, up: Vec3 = (0.0, 1.0, 0.0), fov: Optional[float] = None) -> None:
        """Places the camera (its animation cleared), as a camera path's key does; ``fov`` in radians."""
        if fov is None:
            fov = self.camera["fov"]
        self._core.set_camera(list(position), list(target), list(up), float(fov))

    def apply_camera_path(self, path: "CameraPath", time: float) -> None:
        """The camera of ``path`` at ``time`` seconds and its recorded lights (``bounce render --camera-path``)."""
        for light in path.lights:
            self.set_light(light["name"], light["position"], light["direction"])
        self.set_camera(**path.evaluate(time))

    def __repr__(self) -> str:
        return f"bounce.Scene({self.name!r}, {len(self.lights)} lights, {self.triangles} triangles)"


class CameraPath:
    """A camera path recorded by ``bounce view`` (docs/viewer.md): keys at scene times and the lights' poses."""

    def __init__(self, core: "_bounce.CameraPath"):
        self._core = core

    @staticmethod
    def load(path: Union[str, "_os.PathLike[str]"]) -> "CameraPath":
        """Reads and checks a camera-path JSON file."""
        return CameraPath(_bounce.CameraPath.load(_os.fspath(path)))

    def evaluate(self, time: float) -> dict:
        """The pose at ``time`` seconds (clamped to the keys; exact at a key): keyword arguments of ``Scene.set_camera``."""
        return self._core.evaluate(float(time))

    def frame_range(self, frame_rate: float) -> Tuple[int, int]:
        """First and last frame a replay at ``frame_rate`` renders."""
        return tuple(self._core.frame_range(float(frame_rate)))  # type: ignore[return-value]

    @property
    def lights(self) -> list:
        """``[{"name", "position", "direction"}, ...]`` as the viewer had moved them."""
        return self._core.lights

    @property
    def scene(self) -> str:
        """The scene it was recorded on."""
        return self._core.scene


class Renderer:
    """One technique rendering one scene (``bounce render``), frame by frame.

    ``Renderer(scene, technique, size, settings={...}, component="full")``: ``scene`` a :class:`Scene`
    or a name/path, ``size`` an int, ``(width, height)`` or ``"WxH"``, ``settings`` the technique's
    (``"vplGrid": 16``) and the shared renderer's (``"renderer.shadowMapSize": 1024``) as for ``--set``.
    Frames return the chosen component as float32 numpy arrays of linear radiance (H x W x 3, row 0
    the top, as the CLI's EXR) and the run record as a dict. ``close()`` (or ``with``) gives the GL
    objects back at once; otherwise garbage collection does.
    """

    def __init__(self, scene: Union[Scene, str], technique: str, size: Size = 512,
                 settings: Optional[Mapping[str, Any]] = None, component: str = "full"):
        self.scene = scene if isinstance(scene, Scene) else Scene.load(scene)
        sets = [f"{k}={_value(v)}" for k, v in (settings or {}).items()]
        self._core = _bounce.Renderer(self.scene._core, technique, _size(size), sets, component)
        self._next = 0

    def frame(self, n: Optional[int] = None, time: Optional[float] = None, component: Optional[str] = None) -> Tuple[_np.ndarray, dict]:
        """Renders frame ``n`` (default: the one after the last) and returns ``(image, record)``.

        ``time`` (seconds) shows the scene's animation at that moment instead of ``n / frame_rate``
        (hold the animation while moving lights by hand). The technique sees the frame number (its
        history, interleaving, reseeding). ``component``: ``full``, ``direct`` or ``indirect``.
        """
        n = self._next if n is None else int(n)
        image, record = self._core.frames(1, n, time, component, False)
        self._next = n + 1
        return image, _json.loads(record)

    def frames(self, count: int, start: Optional[int] = None, time: Optional[float] = None,
               component: Optional[str] = None) -> Tuple[_np.ndarray, dict]:
        """Renders ``count`` frames from ``start`` (default: after the last) and returns ``(images, record)``.

        ``images`` is ``count x H x W x 3`` float32, ``record`` holds every frame (per-pass GPU ms,
        counters, live GL objects) and the median pass times, as ``bounce render --frames N --stats``.
        """
        start = self._next if start is None else int(start)
        images, record = self._core.frames(int(count), start, time, component, True)
        self._next = start + int(count)
        return images, _json.loads(record)

    @property
    def settings(self) -> dict:
        """Every setting's value: ``{"technique": {...}, "renderer": {...}}``."""
        s = _json.loads(self._core.settings())
        return {"technique": s["technique"], "renderer": s["renderer"]}

    @property
    def technique(self) -> str:
        """The technique's name."""
        return _json.loads(self._core.settings())["name"]

    @property
    def size(self) -> Tuple[int, int]:
        """(width, height) in pixels."""
        return tuple(_json.loads(self._core.settings())["size"])  # type: ignore[return-value]

    @property
    def component(self) -> str:
        """The component frames return by default."""
        return self._core.component

    def close(self) -> None:
        """Gives the renderer's GL objects back now; later frames raise ``bounce.Error``."""
        self._core.close()

    @property
    def closed(self) -> bool:
        return self._core.closed

    def __enter__(self) -> "Renderer":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    def __repr__(self) -> str:
        return "bounce.Renderer(closed)" if self.closed else f"bounce.Renderer({self.technique!r}, {self.size})"


class Reference:
    """A path-traced reference (``bounce reference``).

    ``image``: float32 H x W x 3 radiance; ``variance``: the per-pixel, per-channel variance of
    ``image`` (the path tracer's sample variance over its n samples, divided by n), the input of the
    noise floors; ``noise``: the run record's noise figures and every metric's floor (what an exact
    image scores against this reference, docs/metrics.md); ``record``: the whole run record.
    """

    def __init__(self, image: _np.ndarray, variance: _np.ndarray, record: dict):
        self.image = image
        self.variance = variance
        self.record = record

    @property
    def noise(self) -> dict:
        return self.record["noise"]

    @property
    def samples_per_pixel(self) -> int:
        return self.record["result"]["samplesPerPixel"]

    def __array__(self, dtype: Any = None) -> _np.ndarray:
        return self.image if dtype is None else self.image.astype(dtype)

    def __repr__(self) -> str:
        h, w = self.image.shape[:2]
        return (f"bounce.Reference({w}x{h}, {self.samples_per_pixel} spp, "
                f"noise {100 * self.noise['meanPixelRelativeStdError']:.2f}% per pixel)")


class PhotonMap:
    """A photon-mapped image (``bounce photon-map``): ``image`` (float32 H x W x 3) and ``record``."""

    def __init__(self, image: _np.ndarray, record: dict):
        self.image = image
        self.record = record

    def __array__(self, dtype: Any = None) -> _np.ndarray:
        return self.image if dtype is None else self.image.astype(dtype)


def _scene(scene: Union[Scene, str]) -> Scene:
    return scene if isinstance(scene, Scene) else Scene.load(scene)


def reference(scene: Union[Scene, str], size: Size = 512, spp: int = 256, bounces: Union[int, str] = "unbounded",
              indirect_only: bool = False, diffuse_only: bool = False, seed: int = 0, frame: int = 0,
              time_limit: float = 0.0, threads: int = 0) -> Reference:
    """Path-traces the scene as it is now (``bounce reference``): returns a :class:`Reference`.

    ``bounces``: indirect bounces K (paths reflect at most K+1 times) or ``"unbounded"``;
    ``indirect_only`` keeps light that reflected at least twice; ``diffuse_only`` the Lambert lobe
    after the first reflection (:func:`reference_scope` gives a technique's). ``frame``: the scene's
    time frame / frame_rate; ``seed``: the same seed gives the same image on any thread count;
    ``time_limit`` (seconds, 0 none) keeps the complete passes within it; ``threads`` 0 = every core.
    """
    s = _scene(scene)
    image, variance, record = _bounce.reference(s._core, _size(size), int(spp), _bounces(bounces), bool(indirect_only),
                                                bool(diffuse_only), int(seed), float(time_limit), int(threads), int(frame))
    return Reference(image, variance, _json.loads(record))


def photon_map(scene: Union[Scene, str], size: Size = 512, photons: int = 1_000_000, k: int = 100, max_radius: float = 0.0,
               spp: int = 4, bounces: Union[int, str] = "unbounded", indirect_only: bool = False,
               diffuse_only: bool = False, seed: int = 0, frame: int = 0, time_limit: float = 0.0,
               threads: int = 0) -> PhotonMap:
    """Renders the scene by photon mapping (``bounce photon-map``, photon splatting's ground truth).

    ``photons`` emitted from the lights, ``k`` nearest photons per estimate, ``max_radius`` caps the
    gather radius (metres, 0 none), ``spp`` jittered gathers per pixel; the rest as :func:`reference`.
    """
    s = _scene(scene)
    image, record = _bounce.photon_map(s._core, _size(size), int(photons), int(k), float(max_radius), int(spp),
                                       _bounces(bounces), bool(indirect_only), bool(diffuse_only), int(seed),
                                       float(time_limit), int(threads), int(frame))
    return PhotonMap(image, _json.loads(record))


ImageLike = Union[_np.ndarray, str, "_os.PathLike[str]", Reference, PhotonMap]


def _image_arg(x: Any) -> Any:
    if isinstance(x, (str, _os.PathLike)):
        return _os.fspath(x)
    if isinstance(x, (Reference, PhotonMap)):
        return x.image
    return _np.asarray(x)


def compare(test: ImageLike, reference: ImageLike, metrics: Optional[Iterable[str]] = None,
            variance: Optional[_np.ndarray] = None, tonemap: str = "aces", exposure: float = 0.0,
            ppd: Optional[float] = None, heatmap: str = "flip") -> dict:
    """Measures ``test`` against ``reference`` (``bounce compare``); arguments in that order.

    Each is an H x W x 3 array of linear radiance, an image file (.exr radiance, .png display image)
    or a :class:`Reference`. Returns a dict of metrics (docs/metrics.md): ``relMse``, ``relRms``,
    ``mse``, ``rmse``, ``mae``, ``nrmse``, ``psnr`` (None when infinite), ``ssim``, ``flipLdr``,
    ``flipHdr``, ``rmsSum8``, ``energy`` (test mean / reference mean), ``testMean``,
    ``referenceMean`` and ``heatmap``, the per-pixel error map as an H x W float32 array (``heatmap``:
    ``flip`` (HDR-FLIP for radiance, LDR-FLIP with a PNG), ``flip-ldr``, ``flip-hdr``, ``relmse``,
    ``abs``). ``metrics=[...]`` keeps only those (names in :data:`METRICS`).

    With the reference's noise (a :class:`Reference`, ``variance=``, or a reference file whose
    ``bounce reference --stats/--variance`` record is beside it) the result also has ``floor`` (each
    metric's value for an exact image against this reference), ``insideFloor`` (the measured error
    within 2x of it: indistinguishable from the reference's noise) and ``relMseCorrected`` (relMSE
    minus its floor). ``tonemap``/``exposure`` are the display transform of radiance inputs for the
    display metrics; ``ppd`` the FLIP observer (pixels per degree).
    """
    wanted = None if metrics is None else list(metrics)
    if wanted is not None:
        unknown = [m for m in wanted if m not in METRICS]
        if unknown:
            raise Error(f"metrics: unknown metric '{unknown[0]}' (known: {', '.join(METRICS)})")
    if variance is None and isinstance(reference, Reference):
        variance = reference.variance
    result_json, heat = _bounce.compare(_image_arg(test), _image_arg(reference),
                                        None if variance is None else _np.asarray(variance), tonemap, exposure,
                                        float(_bounce.flip_default_ppd if ppd is None else ppd), heatmap)
    raw = _json.loads(result_json)
    out: dict = dict(raw["metrics"])
    out.pop("hdrFlipExposures", None)
    out["heatmap"] = heat
    if wanted is not None:
        out = {k: v for k, v in out.items() if k in wanted}
    noise = raw.get("noiseFloor")
    if noise:
        keep = (lambda d: d) if wanted is None else (lambda d: {k: v for k, v in d.items() if k in wanted})
        out["floor"] = keep(noise["floor"])
        out["insideFloor"] = keep(noise["insideFloor"])
        out["relMseCorrected"] = noise["relMseCorrected"]
        out["noise"] = {k: noise[k] for k in ("record", "variance", "samplesPerPixel", "meanPixelRelativeStdError",
                                               "fromRecord", "factor")}
    return out


def flicker(frames: Iterable[Any]) -> float:
    """Temporal flicker of a still-camera sequence (docs/metrics.md): mean over frame pairs and pixels
    of |Y_t - Y_(t-1)| over the mean luminance of all frames (Y: Rec. 709). Two frames give one pair's."""
    return _bounce.flicker([_np.asarray(f) for f in frames])


def sweep(study: Union[str, "_os.PathLike[str]"], out: Optional[Union[str, "_os.PathLike[str]"]] = None,
          progress: bool = False) -> dict:
    """Runs a study (``bounce sweep STUDY.json``, docs/studies.md) in this process.

    Every pending job runs through the same job function as ``bounce sweep --job ID``, one at a time,
    stage 1 then stage 2; finished jobs are skipped, so a second call resumes. (For several jobs at
    once or a cluster, use the command line.) Returns ``{"output", "jobs", "ran", "finished_before",
    "refused", "failed": ["id: reason", ...], "blocked"}``; failures are reported there, not raised.
    """
    return _json.loads(_bounce.sweep(_os.fspath(study), "" if out is None else _os.fspath(out), bool(progress)))


def report(results: Union[str, "_os.PathLike[str]"], out: Optional[Union[str, "_os.PathLike[str]"]] = None) -> str:
    """Writes a study's page (``bounce report``) and results.json / results.csv beside it; returns the page's path."""
    return _bounce.report(_os.fspath(results), "" if out is None else _os.fspath(out))


def read_image(path: Union[str, "_os.PathLike[str]"]) -> _np.ndarray:
    """An image file as float32 H x W x 3: EXR as stored (linear), PNG decoded from sRGB to linear."""
    return _bounce.read_image(_os.fspath(path))


def write_image(path: Union[str, "_os.PathLike[str]"], image: Any, exposure: float = 0.0, tonemap: str = "aces") -> None:
    """Writes linear radiance (H x W x 3): .exr as is, .png through ``exposure`` (stops) and ``tonemap`` (aces, reinhard, clamp); atomically."""
    _bounce.write_image(_os.fspath(path), _np.asarray(image), exposure, tonemap)


def gl_info() -> dict:
    """The module's GL context (made now if needed): vendor, renderer, version, platform, device profile."""
    return _json.loads(_bounce.gl_info())


def select_gpu(index: int) -> None:
    """The EGL device of the module's GL context (``bounce --gpu N``; ``bounce info`` lists them).

    Checked now against the EGL device enumeration (``bounce.Error`` naming the device count
    otherwise); call it before the first renderer, study or :func:`gl_info`, which make the context.
    Without it the environment's ``BOUNCE_EGL_DEVICE`` applies, else the automatic choice (the first
    hardware device, then llvmpipe). Studies run by :func:`sweep` and processes started from Python
    inherit the choice (docs/gpu.md "Device selection").
    """
    _bounce.select_gpu(int(index))


def resources() -> dict:
    """Live GL objects by kind, buffer and texture bytes (gpu/Objects.h) and the process's RSS."""
    return _json.loads(_bounce.resources())


def set_log_level(level: str) -> None:
    """trace, debug, info, warn (the default, as the CLI), error or off."""
    _bounce.set_log_level(level)
