// The docstrings of the `gblens` module's sequence API (app/python/sequence.cpp: open_sequence,
// Sequence, motion, flicker), numpy style, each function's starting with its signature and "--" as
// in docstrings.h (kept apart so that each file stays short).
#pragma once

namespace gb::python::doc {

inline constexpr const char* kOpenSequence = R"(open_sequence(path)
--

Open a sequence folder (``gblens capture --sequence``, ``gblens import --frames``; docs/temporal.md).

Only sequence.json is read here; each frame is read when asked (``seq[i]``, ``seq.frame(n)``,
``seq.array(name)``). One frame alone opens with ``gblens.open("SEQ@N")``.

Parameters
----------
path : str or os.PathLike
    The sequence folder.

Returns
-------
Sequence

Raises
------
gblens.Error
    ``path`` is no sequence or its sequence.json is malformed (the CLI's one line).)";

inline constexpr const char* kSequence = R"(A sequence: consecutive frames, a capture per frame and sequence.json.

``len(seq)`` frames; ``seq.frames`` their numbers, ``seq.times`` and ``seq.jitters`` what the source
said of each; ``seq[i]`` (position) and ``seq.frame(number)`` a ``Frame``, read from disk at each call;
``seq[name]`` and ``seq.array(name)`` a quantity over every frame, time axis first (``stored=True``: a
stored target).)";

inline constexpr const char* kSequencePath = "str: the sequence folder, as given.";
inline constexpr const char* kSequenceManifest = "dict: sequence.json (docs/temporal.md).";
inline constexpr const char* kSequenceFrames = "list of int: the frames' numbers (the N of ``SEQ@N``), increasing.";
inline constexpr const char* kSequenceTimes = "list of float or None: each frame's time in seconds; None where the source did not say.";
inline constexpr const char* kSequenceJitters = R"(list of (float, float) or None: each frame's jitter.

The sub-pixel offset the projection was moved by, in pixels (+x right, +y down); None where the
source did not say (gblens does not assume 0).)";

inline constexpr const char* kSequenceGetItem = R"(__getitem__(self, key)
--

seq[i]: the frame at position ``i`` (negative from the end) as ``seq.frame(seq.frames[i])``;
seq[name]: the quantity ``name`` over every frame, ``seq.array(name)``.)";

inline constexpr const char* kSequenceFrame = R"(frame(self, number)
--

The frame numbered ``number``, as ``gblens.open("SEQ@N")`` opens it (read from disk at each call).

Parameters
----------
number : int
    A frame number of ``frames`` (not a position).

Returns
-------
Frame

Raises
------
gblens.Error
    The sequence has no frame ``number`` (the message names its range), or the frame cannot be read.)";

inline constexpr const char* kSequenceArray = R"(array(self, name, stored=False)
--

A quantity over every frame, time axis first: ``frame[name]`` of each frame, stacked.

Reads and decodes every frame, one at a time; the result holds them all (T times one frame's array:
float64, 8 bytes a component a pixel).

Parameters
----------
name : str
    A quantity's name, as ``Frame[name]`` finds it (case, ``_`` and ``-`` ignored); with ``stored``,
    a stored target's name, as ``Frame.targets`` has it.
stored : bool, default False
    True: the stored target's texels, ``frame.targets[name]`` of each frame, stacked.

Returns
-------
numpy.ndarray
    A quantity: float64 (T, H, W) for a scalar, (T, H, W, C) otherwise, ``array(name)[k]`` equal to
    ``seq[k][name]``. A stored target: (T, H, W, C) in its exact type (as ``Frame.targets``).

Raises
------
gblens.QuantityError
    No quantity of that name (the message lists them).
gblens.ArgumentError
    ``stored``: no target of that name (the message lists them).
gblens.Error
    A frame cannot be read, lacks the target, or differs in size from the first.)";

inline constexpr const char* kMotion = R"(motion(sequence, motion=None, bound=None)
--

Check a sequence's motion vectors by reprojection, as ``gblens motion --json``.

Per pair of consecutive frames: the convention the stored vectors follow (units, direction, y, scale,
jitter, lag) set against the layout's, the error, and each pixel's class (docs/temporal.md).

Parameters
----------
sequence : Sequence or str or os.PathLike
    The sequence, or its folder.
motion : str, optional
    The motion quantity to check (default the layout's first).
bound : float, optional
    The agreement bound in pixels, 0 to 1000 (default derived from the frames' precision).

Returns
-------
dict
    The report, equal to ``gblens motion --json`` (docs/schemas/motion.schema.json): ``verdict``
    ("agrees", "differs", "undecided"), ``findings``, ``pairs``; and ``maps``, per pair (as ``pairs``):
    ``previous``, ``current``, ``error`` (float32 (H, W): |stored - expected| in pixels under the
    layout's convention, NaN off surfaces) and ``class`` (uint32 (H, W): 0 none, 1 static, 2 moving,
    3 disoccluded, 4 wrong).

Raises
------
gblens.ArgumentError
    ``motion`` names no motion quantity, or ``bound`` is out of range.
gblens.Error
    No sequence, a frame cannot be read, or the layout has no motion quantity.)";

inline constexpr const char* kFlicker = R"(flicker(sequence, quantity, reference=None, reproject=True)
--

Per-pixel temporal statistics of a quantity over a sequence, as ``gblens flicker --json``.

Each pixel of the reference frame: its point carried into every frame by reprojection (skipped where
that frame shows something else), the quantity's values there, their standard deviation (ddof 1) and
the largest change between consecutive frames.

Parameters
----------
sequence : Sequence or str or os.PathLike
    The sequence, or its folder.
quantity : str
    A quantity's name, e.g. ``"Albedo"``, ``"Depth"``.
reference : int, optional
    The frame number every frame is carried to (default the first).
reproject : bool, default True
    False: the same pixel in every frame (``--no-reproject``: a still camera).

Returns
-------
dict
    The report, equal to ``gblens flicker --json`` (docs/schemas/flicker.schema.json: ``stddev``'s
    mean and p99, the largest step ``max_step``), and ``maps``: ``stddev`` and ``max_step`` per pixel
    (float32 (H, W), or (H, W, C) for several components; NaN where fewer than two frames saw the
    point) and ``seen`` (uint32 (H, W): how many frames saw it).

Raises
------
gblens.ArgumentError
    ``quantity`` is no quantity of the layout, or ``reference`` no frame of the sequence.
gblens.Error
    No sequence, or a frame cannot be read or differs in size.)";

}  // namespace gb::python::doc
