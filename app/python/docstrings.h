// The `gblens` Python module's docstrings (numpy style), one per class, method and property, kept
// apart from the bindings so that both read easily; tests/python/test_api.py checks every public
// name has one and that app/python/gblens.pyi declares it. A function's starts with its signature
// and "--" (CPython's __text_signature__), so inspect.signature and help() show its real parameters
// (pybind11's own signature lines are turned off in module.cpp). The sequence API's are in
// sequence_docstrings.h.
#pragma once

namespace gb::python::doc {

inline constexpr const char* kOpen = R"(open(path, layout=None, params={}, camera=None, size=None)
--

Open a capture folder, or import files through a layout.

Parameters
----------
path : str or list of str
    A capture folder (``gblens capture``, ``gblens import``); with ``layout``, the file or files to
    import (EXR, PNG, TIFF, raw dumps, Blender passes, one RenderDoc ``.rdc``).
layout : str, optional
    A layout file or ``builtin:NAME``; without it ``path`` is a capture folder.
params : dict, optional
    Option values of a parameterised layout, e.g. ``{"normal_format": "oct-rg16"}``.
camera : str, optional
    A camera sidecar JSON, for layouts that read the camera from one.
size : str, optional
    ``"WxH"``, for raw dumps whose layout does not state it.

Returns
-------
Frame

Raises
------
gblens.Error
    The folder or a file cannot be read, or the layout does not fit them (the CLI's one line).
gblens.ArgumentError
    An argument's value cannot be used (named in the message).)";

inline constexpr const char* kFrame = R"(A frame: a capture, an import or a render.

Its stored targets are numpy arrays over the frame's own memory (``targets``); its quantities are
decoded by its layout (``frame["Normal"]``); ``probe``, ``stats`` and ``check`` are the CLI's commands
on it, ``save`` writes it as a capture.)";

inline constexpr const char* kPath = "str: the capture folder, or what made the frame (\"render builtin:temple\").";
inline constexpr const char* kWidth = "int: the frame's width in pixels.";
inline constexpr const char* kHeight = "int: the frame's height in pixels.";
inline constexpr const char* kLayout = "dict: the frame's layout as JSON (docs/layout-format.md).";
inline constexpr const char* kManifest = "dict: the capture's manifest.json (docs/capture-format.md).";
inline constexpr const char* kCamera = R"(dict: the camera.

``width``, ``height``, ``fov``, ``near``, ``far``, ``reversed_z`` and the matrices ``world_from_eye``,
``eye_from_world``, ``clip_from_eye``, ``eye_from_clip``, ``clip_from_world`` (4x4 row-major float64
arrays; Vulkan clip space, gblens's Y-up world) and ``layout_world_from_world`` (3x3).)";
inline constexpr const char* kTargets = R"(dict of str to numpy.ndarray: the stored texels, (H, W, C).

In their exact type (uint8 for 8-bit and sRGB targets, float16, float32, uint32; uint16 for rgb10a2,
unpacked). No copy: the frame's own memory, read-write; each array keeps the frame alive.)";
inline constexpr const char* kQuantities = R"(list of str: the names of the quantities the frame holds.

Only those whose target the frame has; ``missing_quantities`` lists the others with the reason.)";
inline constexpr const char* kMissingQuantities = R"(dict of str to str: the layout's quantities this frame does not hold, and why.)";

inline constexpr const char* kQuantity = R"(quantity(self, name)
--

A quantity decoded by the layout, as ``probe`` shows it.

Parameters
----------
name : str
    The quantity's name (case, ``_`` and ``-`` ignored), e.g. ``"Normal"``, ``"Depth"``.

Returns
-------
numpy.ndarray
    float64, (H, W) for a scalar (depths, ids, shadow), (H, W, C) for vectors and colours: colours
    linear, normals unit in the layout's space, positions in the layout's space, ids as integers;
    NaN where the quantity has no value (no surface, a depth's background).

Raises
------
gblens.QuantityError
    No quantity of that name (also a KeyError); the message lists the frame's quantities.
gblens.Error
    The frame does not hold the quantity's target.)";

inline constexpr const char* kGetItem = R"(__getitem__(self, name)
--

frame[name]: the quantity ``name`` decoded, as ``quantity(name)``.)";

inline constexpr const char* kPosition = R"(position(self, source="depth", space="world")
--

Positions rebuilt from a depth and the camera, or stored.

Parameters
----------
source : str, default "depth"
    ``"depth"`` (the first camera depth), ``"stored"`` (the stored position) or a depth quantity's name.
space : str, default "world"
    ``"world"`` (the layout's world axes) or ``"eye"``.

Returns
-------
numpy.ndarray
    float64 (H, W, 3); NaN where there is no surface.

Raises
------
gblens.ArgumentError
    ``source`` or ``space`` names nothing the frame has.)";

inline constexpr const char* kMask = R"(mask(self, name="surface")
--

A mask of the frame's pixels.

Parameters
----------
name : str, default "surface"
    ``"surface"`` (a surface was drawn), or compare's masks of this frame alone: ``"silhouettes"``,
    ``"penumbra"``, a mask image file; comma-separated.

Returns
-------
numpy.ndarray
    bool (H, W).)";

inline constexpr const char* kProbe = R"(probe(self, x, y)
--

The pixel dossier, equal to ``gblens probe --json``.

Parameters
----------
x, y : int
    The pixel, top-left origin: 0 <= x < width, 0 <= y < height.

Returns
-------
dict
    Raw and decoded values of every target, positions, lighting (docs/schemas/probe.schema.json).

Raises
------
gblens.ArgumentError
    The pixel is outside the frame.)";

inline constexpr const char* kStats = R"(stats(self, rect, target="", bins=32)
--

Statistics of a rectangle, equal to ``gblens stats --json``.

Parameters
----------
rect : tuple of int or str
    ``(x, y, w, h)`` or ``"x,y,w,h"`` in frame pixels.
target : str, default ""
    Only this target (default every one).
bins : int, default 32
    Histogram bins.

Returns
-------
dict
    Per stored channel (every pixel) and per decoded quantity (surfaces only); each entry says which
    pixels it covers (``surfaces_only``) (docs/schemas/stats.schema.json).

Raises
------
gblens.ArgumentError
    ``rect`` is malformed or reaches outside the frame, or ``target`` is not one of the frame's.)";

inline constexpr const char* kCheck = R"(check(self, policy=None)
--

NaN, infinities, denormals, out-of-range values, positions and normals checked, as ``gblens check --json``.

Parameters
----------
policy : list of str or dict, optional
    ``check --policy``'s rules: ``["denormal=fault", "Normal.out_of_range=warn"]`` or
    ``{"denormal": "fault"}``.

Returns
-------
dict
    The report (docs/schemas/check.schema.json); ``clean`` is True when nothing is a fault.

Raises
------
gblens.ArgumentError
    A rule is malformed.)";

inline constexpr const char* kSave = R"(save(self, dir)
--

Write the frame as a capture folder, atomically (a folder beside it, renamed into place).

Parameters
----------
dir : str or os.PathLike
    The capture folder to write.

Raises
------
gblens.Error
    The folder cannot be written.)";

inline constexpr const char* kResult = R"(What ``gblens.compare`` found: the verdict, each group's figures, the per-pixel errors.)";
inline constexpr const char* kExitCode = "int: idiff's exit code: 0 pass, 1 warn, 2 fail, 3 mismatch.";
inline constexpr const char* kPassed = "bool: True for pass and warn (exit code 0 or 1).";
inline constexpr const char* kResultName = "str: \"pass\", \"warn\", \"fail\" or \"mismatch\".";
inline constexpr const char* kJson = "dict: the report, equal to ``gblens compare --json`` (docs/schemas/compare.schema.json).";
inline constexpr const char* kGroups = "dict of str to dict: each compared group's entry of ``json``, by key (\"hdr\", \"normal_shadow.Normal\").";
inline constexpr const char* kFlip = "list of dict: the FLIP entries of ``json``.";
inline constexpr const char* kText = "str: the console summary, as ``gblens compare`` prints it.";
inline constexpr const char* kResultMask = "numpy.ndarray or None: the mask bits, uint8 (H, W): 1 silhouettes, 2 penumbra, 4 file.";
inline constexpr const char* kErrors = R"(errors(self, key)
--

The per-pixel error of a group or FLIP entry.

Parameters
----------
key : str
    A group's key (``"hdr"``) or ``"flip.final"`` / ``"flip.hdr"``.

Returns
-------
numpy.ndarray
    float32 (H, W), the result's own memory; NaN where not compared.

Raises
------
gblens.QuantityError
    No group or FLIP entry of that key (also a KeyError).)";
inline constexpr const char* kReport = R"(report(self, dir)
--

Write the review page (docs/report.md) into a folder.

Parameters
----------
dir : str or os.PathLike
    The report folder (an existing report there is replaced).)";
inline constexpr const char* kJunit = R"(junit(self, file, name="")
--

Write JUnit XML (docs/json.md#junit).

Parameters
----------
file : str or os.PathLike
    The XML file.
name : str, default ""
    The test suite's name ("gblens compare" when empty).)";
inline constexpr const char* kWriteImages = R"(write_images(self, dir)
--

Write what ``gblens compare -o DIR`` writes: heat maps with legends, FLIP maps, the mask.

Parameters
----------
dir : str or os.PathLike
    The folder.)";

inline constexpr const char* kCompare = R"(compare(a, b, *, fail=None, failpercent=None, hardfail=None, warn=None, warnpercent=None, mask=None, exclude=[], flip=True, fail_flip=None, warn_flip=None, flip_ppd=None)
--

Compare two frames target by target, as ``gblens compare`` does.

Parameters
----------
a, b : Frame or str
    Frames or capture folders.
fail, failpercent, hardfail, warn, warnpercent : float or dict, optional
    idiff's thresholds: a number for every group, or ``{"": 0.01, "hdr": 0.05,
    "normal_shadow.Normal": 0.1}`` per target or group.
mask : str, optional
    Pixels reported apart, deciding nothing: ``"silhouettes,penumbra,FILE"``.
exclude : list of str, optional
    Targets left out.
flip : bool, default True
    FLIP of final and hdr.
fail_flip, warn_flip : float or dict, optional
    Thresholds on the mean FLIP (``{"final": 0.05}``).
flip_ppd : float, optional
    FLIP's pixels per degree.

Returns
-------
Result

Raises
------
gblens.ArgumentError
    A threshold or option is malformed (named as its keyword: ``fail=abc: ...``).
gblens.Error
    A capture cannot be read.)";

inline constexpr const char* kRender = R"(render(scene="builtin:temple", *, targets=None, device="", coverage=True, **options)
--

Render one frame headless, as ``gblens capture`` renders it.

Parameters
----------
scene : str, default "builtin:temple"
    ``builtin:NAME`` or a glTF file.
targets : list of str, optional
    The targets to read back (default every available one).
device : str, default ""
    A Vulkan device name part (default: a real GPU first, else lavapipe).
coverage : bool, default True
    The coverage-count targets.
**options
    Options by their option-table names: ``size=(w, h)`` or ``"WxH"``, ``lights=16``,
    ``normal_format="oct-rg16"``, ``primitive_id=True`` ...

Returns
-------
Frame

Raises
------
gblens.ArgumentError
    An option is unknown or its value malformed (named as its keyword).)";

inline constexpr const char* kError = R"(error(scene="builtin:temple", *, device="", band=2.0, **options)
--

One frame's error per quantity against the double-precision CPU reference.

Parameters
----------
scene : str, default "builtin:temple"
    As ``render``.
device : str, default ""
    As ``render``.
band : float, default 2.0
    The shadow-edge band (texels) reported apart.
**options
    As ``render``.

Returns
-------
dict
    The figures of ``gblens error --json``.)";

}  // namespace gb::python::doc
