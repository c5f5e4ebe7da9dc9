"""gblens's RenderDoc replay: lists a capture and reads raw texels and buffer bytes from it.

gblens carries this script inside its binary (cmake/EmbedText.cmake) and runs it with the system
/usr/bin/python3 and Debian's python3-renderdoc (views/import/renderdoc_replay.cpp). Commands:
  list RDC                          JSON on stdout: api, driver, passes, textures, last event
  texels RDC EVENT OUTDIR TEX...    OUTDIR/<i>.bin: the stored bits of each texture (a name or #id)
                                    after EVENT (0: the end of the pass that last writes it), packed
                                    as gblens packs read-backs (renderer/core/texels.h); JSON on stdout
  buffer RDC EVENT BUFFER OUT       OUT: the bytes of a buffer (a name or #id) at EVENT (0: its first use)
  state RDC OUTDIR [--bytes] EVENT...  OUTDIR/state_<EVENT>.json: the buffers bound at the last draw or
                                    dispatch up to each EVENT (set, binding, range; --bytes: their bytes)
A problem prints one line on stderr and exits 2. Progress lines start with "progress:" (the caller
shows the last one when the replay runs out of time).
"""
import json
import os
import sys

import renderdoc as rd

# How a texture can be written (RenderDoc's ResourceUsage): the writes of a pass.
WRITES = {
    rd.ResourceUsage.ColorTarget, rd.ResourceUsage.DepthStencilTarget, rd.ResourceUsage.Clear,
    rd.ResourceUsage.CopyDst, rd.ResourceUsage.Copy, rd.ResourceUsage.ResolveDst, rd.ResourceUsage.Resolve,
    rd.ResourceUsage.GenMips, rd.ResourceUsage.VS_RWResource, rd.ResourceUsage.HS_RWResource,
    rd.ResourceUsage.DS_RWResource, rd.ResourceUsage.GS_RWResource, rd.ResourceUsage.PS_RWResource,
    rd.ResourceUsage.CS_RWResource, rd.ResourceUsage.All_RWResource,
}


# How a texture can be read (the reads that make a pass's output an input of a later one): sampled or
# loaded by a shader stage, an input attachment, the source of a copy, blit or resolve.
READS = {
    rd.ResourceUsage.VS_Resource, rd.ResourceUsage.HS_Resource, rd.ResourceUsage.DS_Resource,
    rd.ResourceUsage.GS_Resource, rd.ResourceUsage.PS_Resource, rd.ResourceUsage.CS_Resource,
    rd.ResourceUsage.All_Resource, rd.ResourceUsage.InputTarget, rd.ResourceUsage.CopySrc,
    rd.ResourceUsage.ResolveSrc, rd.ResourceUsage.Copy, rd.ResourceUsage.Resolve,
}


class Failure(Exception):
    pass


def progress(text):
    print("progress: " + text, file=sys.stderr, flush=True)


def rid_int(rid):
    return int(rid)


def enum_name(cls, value):
    """The bindings' enums are plain ints: their names come from the class's constants."""
    for name in dir(cls):
        if name[:1].isupper() and isinstance(getattr(cls, name), int) and getattr(cls, name) == value:
            return name
    return str(value)


def local_gpus(cap):
    gpus = ["%s (%s)" % (g.name, g.driver) if g.driver else g.name for g in cap.GetAvailableGPUs()]
    return ", ".join(gpus) if gpus else "no GPU RenderDoc can use"


def recorded_device(sfile):
    """The recording GPU and driver, where the capture says (Vulkan: the physical device properties
    serialised with vkEnumeratePhysicalDevices near the start); {} when it does not."""
    wanted = {"deviceName": "device", "driverName": "driver", "driverInfo": "driver_info"}
    found = {}

    def walk(o, depth):
        for i in range(o.NumChildren()):
            ch = o.GetChild(i)
            if ch.name in wanted and ch.NumChildren() == 0 and wanted[ch.name] not in found:
                value = ch.AsString()
                if value:
                    found[wanted[ch.name]] = value
            elif depth < 3:
                walk(ch, depth + 1)

    for chunk in list(sfile.chunks)[:200]:
        if chunk.name == "vkEnumeratePhysicalDevices":
            walk(chunk, 0)
            break
    return found


class Replay:
    """An open capture: the controller, names of resources, the action tree flattened."""

    def __init__(self, path):
        self.path = path
        progress("opening " + path)
        self.cap = rd.OpenCaptureFile()
        result = self.cap.OpenFile(path, "", None)
        if not result.OK():
            raise Failure("%s: RenderDoc cannot open it: %s" % (path, result.Message()))
        self.api = self.cap.DriverName()
        machine = self.cap.RecordedMachineIdent().strip()
        if self.cap.LocalReplaySupport() == rd.ReplaySupport.Unsupported:
            raise Failure("%s: a %s capture (recorded on %s) that RenderDoc %s cannot replay on this machine (%s)"
                          % (path, self.api, machine, rd.GetVersionString(), local_gpus(self.cap)))
        progress("replaying the %s capture on %s" % (self.api, local_gpus(self.cap)))
        result, self.controller = self.cap.OpenCapture(rd.ReplayOptions(), None)
        if not result.OK():
            raise Failure("%s: RenderDoc %s could not replay this %s capture (recorded on %s) on this machine's "
                          "driver, %s: %s" % (path, rd.GetVersionString(), self.api, machine, local_gpus(self.cap),
                                              result.Message()))
        props = self.controller.GetAPIProperties()
        self.driver = "%s capture recorded on %s, replayed by RenderDoc %s on %s%s" % (
            self.api, machine, rd.GetVersionString(), local_gpus(self.cap),
            " (degraded: a different GPU than recorded)" if props.degraded else "")
        self.sfile = self.controller.GetStructuredFile()
        self.provenance = {
            "recorded": dict({"api": self.api, "machine": machine}, **recorded_device(self.sfile)),
            "replay": {"renderdoc": rd.GetVersionString(), "device": local_gpus(self.cap),
                       "degraded": bool(props.degraded)}}
        self.names = {rid_int(r.resourceId): r.name for r in self.controller.GetResources()}
        # Names RenderDoc made up ("2D Image 127"): the application named nothing.
        self.auto = {rid_int(r.resourceId) for r in self.controller.GetResources() if r.autogeneratedName}
        self.textures = {rid_int(t.resourceId): t for t in self.controller.GetTextures()}
        self.buffers = {rid_int(b.resourceId): b for b in self.controller.GetBuffers()}
        self.actions = []  # (action, depth) in event order
        self._flatten(self.controller.GetRootActions(), 0)
        self.last_event = max([last_event(a) for a, _ in self.actions] + [0])
        self._passes = None

    def _flatten(self, actions, depth):
        for a in actions:
            self.actions.append((a, depth))
            self._flatten(a.children, depth + 1)

    def close(self):
        self.controller.Shutdown()
        self.cap.Shutdown()

    def reads(self, tex_id):
        return sorted(set(u.eventId for u in self.controller.GetUsage(self.textures[tex_id].resourceId)
                          if u.usage in READS))

    def compute_writes(self, tex_id):
        """Dispatches that bind it as a storage image (RenderDoc: CS_RWResource): may write it."""
        return sorted(set(u.eventId for u in self.controller.GetUsage(self.textures[tex_id].resourceId)
                          if u.usage == rd.ResourceUsage.CS_RWResource))

    def writes(self, tex_id):
        return sorted(u.eventId for u in self.controller.GetUsage(self.textures[tex_id].resourceId)
                      if u.usage in WRITES)

    def passes(self):
        """Label regions (every one, nested ones too), and render passes not already named by a
        region that holds no other render pass."""
        if self._passes is None:
            self._passes = self._find_passes()
        return [dict(p) for p in self._passes]

    def _find_passes(self):
        regions = []
        for a, depth in self.actions:
            if a.flags & rd.ActionFlags.PushMarker:
                regions.append({"name": a.GetName(self.sfile), "first": a.eventId, "last": last_event(a),
                                "depth": depth})
        render_passes, begin = [], None
        for a, depth in self.actions:
            if a.flags & rd.ActionFlags.BeginPass:
                begin = (a, depth)
            elif a.flags & rd.ActionFlags.EndPass and begin:
                render_passes.append((begin[0], a.eventId, begin[1]))
                begin = None

        def inside(r, first, last):
            return r["first"] <= first and last <= r["last"]

        for n, (a, end, depth) in enumerate(render_passes):
            named = False
            for r in regions:
                if inside(r, a.eventId, end):
                    held = [p for p in render_passes if inside(r, p[0].eventId, p[1])]
                    named = named or len(held) == 1
            if not named:
                regions.append({"name": "render pass %d: %s" % (n + 1, a.GetName(self.sfile)), "first": a.eventId,
                                "last": end, "depth": depth})
        regions.sort(key=lambda r: (r["first"], -r["last"]))
        return regions

    def find(self, table, kind, wanted):
        if wanted.startswith("#"):
            try:
                rid = int(wanted[1:])
            except ValueError:
                raise Failure("%s: %s \"%s\": an id is # and a number (see --list)" % (self.path, kind, wanted))
            if rid not in table:
                raise Failure("%s: no %s with id %s (see --list)" % (self.path, kind, wanted))
            return rid
        ids = [i for i in table if self.names.get(i) == wanted]
        if not ids:
            raise Failure("%s: no %s named \"%s\" (%ss: %s)" % (self.path, kind, wanted, kind,
                                                             ", ".join(sorted(set(self.names[i] for i in table)))))
        if len(ids) > 1:
            raise Failure("%s: %d %ss are named \"%s\": name one by id (%s)" % (
                self.path, len(ids), kind, wanted, ", ".join("#%d" % i for i in ids)))
        return ids[0]

    def check_event(self, event):
        if event > self.last_event:
            raise Failure("%s: event %d is out of range (the capture's events are 1..%d)"
                          % (self.path, event, self.last_event))


def last_event(action):
    last = max([action.eventId] + [e.eventId for e in action.events])
    for c in action.children:
        last = max(last, last_event(c))
    return last


def describe_format(fmt):
    return {"name": fmt.Name(), "type": enum_name(rd.ResourceFormatType, fmt.type),
            "compType": enum_name(rd.CompType, fmt.compType),
            "compCount": fmt.compCount, "compByteWidth": fmt.compByteWidth, "bgra": bool(fmt.BGRAOrder())}


def describe_texture(replay, tex_id):
    t = replay.textures[tex_id]
    return {"name": replay.names.get(tex_id, "#%d" % tex_id), "id": tex_id, "auto": tex_id in replay.auto,
            "format": describe_format(t.format),
            "width": t.width, "height": t.height, "depth": t.depth, "mips": t.mips, "arraysize": t.arraysize,
            "samples": t.msSamp, "reads": replay.reads(tex_id), "compute_writes": replay.compute_writes(tex_id),
            "presented": bool(int(t.creationFlags) & int(rd.TextureCategory.SwapBuffer))}


def child(obj, name):
    for i in range(obj.NumChildren()):
        if obj.GetChild(i).name == name:
            return obj.GetChild(i)
    return None


def children(obj):
    return [obj.GetChild(i) for i in range(obj.NumChildren())] if obj is not None else []


def store_name(obj):
    """VK_ATTACHMENT_STORE_OP_DONT_CARE -> dont_care (None: not given)."""
    if obj is None:
        return None
    text = obj.AsString()
    return text.replace("VK_ATTACHMENT_STORE_OP_", "").replace("_KHR", "").replace("_EXT", "").replace("_QCOM", "").lower() or None


def attachment_stores(replay):
    """The application's own store ops of each render pass's attachments, by the begin event: {event:
    {image id: {"store", "stencil_store"}}}, read from the capture's creation chunks (vkCreateRenderPass(2),
    vkCreateFramebuffer, vkCreateImageView) and each vkCmdBeginRenderPass(2) / vkCmdBeginRendering."""
    rps, fbs, views = {}, {}, {}
    sf = replay.sfile
    for ch in sf.chunks:
        if ch.name in ("vkCreateRenderPass", "vkCreateRenderPass2", "vkCreateRenderPass2KHR"):
            made = child(ch, "RenderPass")
            info = child(ch, "CreateInfo")
            if made is None or info is None:
                continue
            rps[int(made.AsResourceId())] = [(store_name(child(a, "storeOp")), store_name(child(a, "stencilStoreOp")))
                                             for a in children(child(info, "pAttachments"))]
        elif ch.name == "vkCreateFramebuffer":
            made, info = child(ch, "Framebuffer"), child(ch, "CreateInfo")
            if made is not None and info is not None:
                fbs[int(made.AsResourceId())] = [int(v.AsResourceId()) for v in children(child(info, "pAttachments"))]
        elif ch.name == "vkCreateImageView":
            made, info = child(ch, "View"), child(ch, "CreateInfo")
            if made is not None and info is not None and child(info, "image") is not None:
                views[int(made.AsResourceId())] = int(child(info, "image").AsResourceId())
    out = {}
    for a, _ in replay.actions:
        if not a.flags & rd.ActionFlags.BeginPass or not a.events:
            continue
        ch = sf.chunks[a.events[-1].chunkIndex]
        found = {}
        begin = child(ch, "RenderPassBegin")
        if begin is not None:
            rp, fb = child(begin, "renderPass"), child(begin, "framebuffer")
            ops = rps.get(int(rp.AsResourceId()), []) if rp is not None else []
            atts = fbs.get(int(fb.AsResourceId()), []) if fb is not None else []
            for i, view in enumerate(atts):
                if i < len(ops) and view in views:
                    found[views[view]] = {"store": ops[i][0], "stencil_store": ops[i][1]}
        info = child(ch, "RenderingInfo")
        if info is not None:  # dynamic rendering: each attachment names its view and store op
            for name in ("pColorAttachments", "pDepthAttachment", "pStencilAttachment"):
                for att in (children(child(info, name)) if name == "pColorAttachments" else [child(info, name)]):
                    view = child(att, "imageView") if att is not None else None
                    if view is None or int(view.AsResourceId()) not in views:
                        continue
                    entry = found.setdefault(views[int(view.AsResourceId())], {"store": None, "stencil_store": None})
                    entry["stencil_store" if name == "pStencilAttachment" else "store"] = store_name(child(att, "storeOp"))
        out[a.eventId] = found
    return out


# Buffer descriptors (RenderDoc's BindType) and what gblens calls them.
BUFFER_KINDS = {rd.BindType.ConstantBuffer: "uniform", rd.BindType.ReadOnlyBuffer: "storage",
                rd.BindType.ReadWriteBuffer: "storage"}
STAGES = [(rd.ShaderStage.Vertex, "vertex"), (rd.ShaderStage.Hull, "tess_control"),
          (rd.ShaderStage.Domain, "tess_eval"), (rd.ShaderStage.Geometry, "geometry"),
          (rd.ShaderStage.Pixel, "fragment"), (rd.ShaderStage.Compute, "compute")]
# RenderDoc's usage prefixes (VS_Constants, PS_RWResource, ...) -> stage names.
USAGE_STAGES = {"VS": "vertex", "HS": "tess_control", "DS": "tess_eval", "GS": "geometry", "PS": "fragment",
                "CS": "compute", "All": "all"}
WHOLE = 0xFFFFFFFFFFFFFFFF


def last_work(replay, first, last):
    """The last draw or dispatch with an event in first..last, or None."""
    work = rd.ActionFlags.Drawcall | rd.ActionFlags.Dispatch
    found = None
    for a, _ in replay.actions:
        if first <= a.eventId <= last and a.flags & work:
            found = a
    return found


def uses_by_event(replay):
    """What each event uses, from RenderDoc's usage records (no replay needed): colour and depth
    targets, and the buffers read as constants or resources, with the stages that read them."""
    uses = {}

    def at(e):
        return uses.setdefault(e, {"outputs": [], "depthTarget": "", "buffers": {}})
    name = lambda i: replay.names.get(i, "#%d" % i)
    for tex_id, t in sorted(replay.textures.items()):
        for u in replay.controller.GetUsage(t.resourceId):
            if u.usage == rd.ResourceUsage.ColorTarget and name(tex_id) not in at(u.eventId)["outputs"]:
                at(u.eventId)["outputs"].append(name(tex_id))
            elif u.usage == rd.ResourceUsage.DepthStencilTarget:
                at(u.eventId)["depthTarget"] = name(tex_id)
    for buf_id, b in sorted(replay.buffers.items()):
        for u in replay.controller.GetUsage(b.resourceId):
            prefix, _, what = enum_name(rd.ResourceUsage, u.usage).partition("_")
            if prefix not in USAGE_STAGES or what not in ("Constants", "Resource", "RWResource"):
                continue
            entry = at(u.eventId)["buffers"].setdefault(buf_id, {
                "id": buf_id, "name": name(buf_id), "auto": buf_id in replay.auto, "bytes": b.length,
                "kind": "uniform" if what == "Constants" else "storage", "stages": []})
            if USAGE_STAGES[prefix] not in entry["stages"]:
                entry["stages"].append(USAGE_STAGES[prefix])
    return uses


def reflected_members(pipe, compute):
    """(set, binding) -> the members the shaders declare in that buffer: [name, byte offset, type]."""
    members = {}
    for stage, _ in STAGES:
        if (stage == rd.ShaderStage.Compute) != compute:
            continue
        refl = pipe.GetShaderReflection(stage)
        if refl is None:
            continue
        mapping = pipe.GetBindpointMapping(stage)
        for cb in refl.constantBlocks:
            if cb.bufferBacked and cb.bindPoint < len(mapping.constantBlocks):
                bp = mapping.constantBlocks[cb.bindPoint]
                members[(bp.bindset, bp.bind)] = [[v.name, v.byteOffset, v.type.name] for v in cb.variables]
        for res in list(refl.readOnlyResources) + list(refl.readWriteResources):
            table = mapping.readOnlyResources if res.isReadOnly else mapping.readWriteResources
            if not res.isTexture and res.bindPoint < len(table):
                bp = table[res.bindPoint]
                members.setdefault((bp.bindset, bp.bind), [[v.name, v.byteOffset, v.type.name]
                                                           for v in res.variableType.members])
    return members


def draw_state(replay, compute):
    """The viewport of the current draw (none for a dispatch)."""
    if compute:
        return {}
    v = replay.controller.GetPipelineState().GetViewport(0)
    return {"viewport": [v.x, v.y, v.width, v.height]}


def bound_now(replay, compute):
    """The uniform and storage buffers bound at the current draw or dispatch: the buffer, where it is
    bound (set, binding, array index, stages) and the bound byte range."""
    out = []
    if replay.controller.GetAPIProperties().pipelineType == rd.GraphicsAPI.Vulkan:
        vk = replay.controller.GetVulkanPipelineState()
        members = reflected_members(replay.controller.GetPipelineState(), compute)
        for set_index, ds in enumerate((vk.compute if compute else vk.graphics).descriptorSets):
            for binding, b in enumerate(ds.bindings):
                stages = [n for i, (_, n) in enumerate(STAGES) if b.stageFlags & (1 << i)]
                for index, e in enumerate(b.binds):
                    kind = BUFFER_KINDS.get(e.type)
                    buf_id = rid_int(e.resourceResourceId)
                    if kind is None or buf_id not in replay.buffers:
                        continue
                    length = replay.buffers[buf_id].length
                    size = length - e.byteOffset if e.byteSize == WHOLE else e.byteSize
                    out.append({"id": buf_id, "name": replay.names.get(buf_id, "#%d" % buf_id), "kind": kind,
                                "auto": buf_id in replay.auto, "bytes": length, "set": set_index,
                                "binding": binding, "index": index, "stages": stages, "offset": e.byteOffset,
                                "range": min(size, length - e.byteOffset),
                                "members": members.get((set_index, binding), [])})
        return out
    # Other APIs: the constant buffers the shaders reflect.
    pipe = replay.controller.GetPipelineState()
    seen = {}
    for stage, stage_name in STAGES:
        refl = pipe.GetShaderReflection(stage)
        if refl is None or (stage == rd.ShaderStage.Compute) != compute:
            continue
        mapping = pipe.GetBindpointMapping(stage)
        for i, cb in enumerate(refl.constantBlocks):
            bound = pipe.GetConstantBuffer(stage, i, 0)
            buf_id = rid_int(bound.resourceId)
            if not cb.bufferBacked or buf_id not in replay.buffers:
                continue
            bp = mapping.constantBlocks[cb.bindPoint]
            key = (buf_id, bp.bindset, bp.bind)
            if key in seen:
                seen[key]["stages"].append(stage_name)
                continue
            length = replay.buffers[buf_id].length
            seen[key] = {"id": buf_id, "name": replay.names.get(buf_id, "#%d" % buf_id), "kind": "uniform",
                         "auto": buf_id in replay.auto, "bytes": length, "set": bp.bindset, "binding": bp.bind,
                         "index": 0, "stages": [stage_name], "offset": bound.byteOffset,
                         "range": min(bound.byteSize or length, length - bound.byteOffset),
                         "members": [[v.name, v.byteOffset, v.type.name] for v in cb.variables]}
            out.append(seen[key])
    return out


def command_list(replay):
    passes = replay.passes()
    writers = {}
    for tex_id in replay.textures:
        writers[tex_id] = replay.writes(tex_id)
    uses = uses_by_event(replay)
    stores = attachment_stores(replay)
    for p in passes:
        p["stores"] = [dict(v, id=tex_id) for e, found in sorted(stores.items()) if p["first"] <= e <= p["last"]
                       for tex_id, v in sorted(found.items()) if tex_id in replay.textures]
        p["writes"] = [tex_id for tex_id, events in sorted(writers.items())
                       if any(p["first"] <= e <= p["last"] for e in events)]
        work = last_work(replay, p["first"], p["last"])
        p["boundAt"] = work.eventId if work else 0
        used = uses.get(p["boundAt"], {"outputs": [], "depthTarget": "", "buffers": {}})
        p.update({"outputs": used["outputs"], "depthTarget": used["depthTarget"],
                  "buffers": list(used["buffers"].values())})
    return {"api": replay.api, "driver": replay.driver, "provenance": replay.provenance,
            "lastEvent": replay.last_event, "passes": passes,
            "textures": [describe_texture(replay, i) for i in sorted(replay.textures)],
            "buffers": [{"id": i, "name": replay.names.get(i, "#%d" % i), "bytes": b.length}
                        for i, b in sorted(replay.buffers.items())]}


def command_state(replay, outdir, with_bytes, events):
    """Per event (a draw or dispatch; 0: the frame's last): OUTDIR/state_<event>.json with the buffers
    bound there (and with --bytes, OUTDIR/b<event>_<i>.bin, each one's bound range) and the viewport.
    One file as each event is done: RenderDoc 1.24 can crash moving between some events on some
    drivers, and the caller keeps what was written and starts again after it."""
    for event in events:
        replay.check_event(event)
        action = last_work(replay, 1, event or replay.last_event)
        if action is None:
            raise Failure("%s: no draw or dispatch up to event %d" % (replay.path, event))
        progress("reading the state at event %d" % action.eventId)
        replay.controller.SetFrameEvent(action.eventId, False)
        compute = bool(action.flags & rd.ActionFlags.Dispatch)
        result = {"event": action.eventId, "buffers": bound_now(replay, compute)}
        result.update(draw_state(replay, compute))
        if with_bytes:
            for i, b in enumerate(result["buffers"]):
                b["file"] = os.path.join(outdir, "b%d_%d.bin" % (event, i))
                with open(b["file"], "wb") as f:
                    f.write(bytes(replay.controller.GetBufferData(replay.buffers[b["id"]].resourceId, b["offset"],
                                                                  b["range"])))
        path = os.path.join(outdir, "state_%d.json" % event)
        with open(path + ".tmp", "w") as f:
            json.dump(result, f)
        os.replace(path + ".tmp", path)
    return {"events": events}


def default_event(replay, tex_id):
    """After the last write: the end of the innermost label region holding it (its pass), else the
    write itself; a texture the frame never writes is read at the end of the frame."""
    events = replay.writes(tex_id)
    if not events:
        return replay.last_event
    write = events[-1]
    holding = [r for r in replay.passes() if r["first"] <= write <= r["last"]]
    return min(holding, key=lambda r: r["last"] - r["first"])["last"] if holding else write


def packed(data, fmt, width, height):
    """RenderDoc 1.24's Vulkan GetTextureData interleaves depth and stencil (vk_replay.cpp: D32S8 as
    two 32-bit words a texel, D24S8 as one word with stencil in the top byte, D16S8 as two 16-bit
    words); gblens packs the depth plane, then one stencil byte a texel."""
    n = width * height
    kind = enum_name(rd.ResourceFormatType, fmt.type)
    data = bytes(data)
    if kind == "D32S8":
        expect(data, 8 * n)
        words = memoryview(data).cast("I")
        return words[0::2].tobytes() + data[4::8]
    if kind == "D24S8":
        # 1.24 sizes the buffer for separate planes (4 + 1 bytes a texel) but interleaves into the
        # first 4 bytes a texel; the rest is unused.
        expect(data, 4 * n, at_least=True)
        depth = bytearray(data[:4 * n])
        depth[3::4] = bytes(n)  # the top byte of X8_D24 holds nothing
        return bytes(depth) + data[3:4 * n:4]
    if kind == "D16S8":
        expect(data, 4 * n)
        return memoryview(data).cast("H")[0::2].tobytes() + data[2::4]
    if fmt.BGRAOrder() and kind == "Regular" and fmt.compCount == 4 and fmt.compByteWidth == 1:
        # B8G8R8A8: R and B swapped back, as the gblens layer streams it (rgba8_unorm / rgba8_srgb).
        swapped = bytearray(data)
        swapped[0::4], swapped[2::4] = data[2::4], data[0::4]
        return bytes(swapped)
    return data


def expect(data, size, at_least=False):
    if len(data) < size or (len(data) != size and not at_least):
        raise Failure("RenderDoc returned %d bytes of depth/stencil texels, expected %d" % (len(data), size))


def command_texels(replay, event, outdir, wanted):
    replay.check_event(event)
    out = []
    for i, name in enumerate(wanted):
        tex_id = replay.find(replay.textures, "texture", name)
        t = replay.textures[tex_id]
        if t.depth > 1 or t.arraysize > 1:
            raise Failure("%s: texture %s is 3D or an array; gblens reads 2D textures" % (replay.path, name))
        at = event or default_event(replay, tex_id)
        progress("reading %s after event %d" % (name, at))
        replay.controller.SetFrameEvent(at, False)
        # A multisampled texture: every sample (RenderDoc's Subresource selects one), one plane each,
        # sample 0 first, in the file one after another.
        planes = []
        for k in range(max(1, t.msSamp)):
            data = replay.controller.GetTextureData(t.resourceId, rd.Subresource(0, 0, k))
            if not data:
                raise Failure("%s: RenderDoc returned no texels for %s%s at event %d" % (
                    replay.path, name, " sample %d" % k if t.msSamp > 1 else "", at))
            planes.append(packed(data, t.format, t.width, t.height))
        path = os.path.join(outdir, "%d.bin" % i)
        with open(path, "wb") as f:
            for plane in planes:
                f.write(plane)
        entry = describe_texture(replay, tex_id)
        entry.update({"event": at, "file": path, "sample_bytes": len(planes[0])})
        out.append(entry)
    return {"textures": out}


def buffers_with_bindings(replay, event):
    """Every buffer as "name #id N bytes", with where the last draw up to EVENT binds it: what a
    wrong buffer name is answered with."""
    bound = {}
    action = last_work(replay, 1, event or replay.last_event)
    if action is not None:
        replay.controller.SetFrameEvent(action.eventId, False)
        for b in bound_now(replay, bool(action.flags & rd.ActionFlags.Dispatch)):
            bound.setdefault(b["id"], "%s at set %d binding %d" % (b["kind"], b["set"], b["binding"]))
    return ", ".join("%s #%d %d bytes%s" % (replay.names.get(i, ""), i, b.length,
                                             " (%s, event %d)" % (bound[i], action.eventId) if i in bound else "")
                     for i, b in sorted(replay.buffers.items()))


def command_buffer(replay, event, wanted, outpath):
    replay.check_event(event)
    try:
        buf_id = replay.find(replay.buffers, "buffer", wanted)
    except Failure:
        if wanted.startswith("#"):
            raise
        raise Failure("%s: no buffer named \"%s\" (buffers: %s)" % (replay.path, wanted,
                                                                     buffers_with_bindings(replay, event)))
    b = replay.buffers[buf_id]
    at = event
    if not at:
        uses = sorted(u.eventId for u in replay.controller.GetUsage(b.resourceId) if u.eventId > 0)
        at = uses[0] if uses else replay.last_event
    replay.controller.SetFrameEvent(at, False)
    progress("reading buffer %s at event %d" % (wanted, at))
    data = replay.controller.GetBufferData(b.resourceId, 0, 0)
    with open(outpath, "wb") as f:
        f.write(bytes(data))
    return {"name": replay.names.get(buf_id, "#%d" % buf_id), "id": buf_id, "event": at, "bytes": len(data)}


def main(argv):
    if len(argv) < 3 or argv[1] not in ("list", "texels", "buffer", "state"):
        raise Failure("usage: renderdoc_replay.py list RDC | texels RDC EVENT OUTDIR TEX... | buffer RDC EVENT BUF OUT"
                      " | state RDC OUTDIR [--bytes] EVENT...")
    command, path = argv[1], argv[2]
    if not os.path.isfile(path):
        raise Failure("%s: no such file" % path)
    rd.InitialiseReplay(rd.GlobalEnvironment(), [])
    replay = Replay(path)
    try:
        if command == "list":
            result = command_list(replay)
        elif command == "texels":
            result = command_texels(replay, int(argv[3]), argv[4], argv[5:])
        elif command == "state":
            with_bytes = "--bytes" in argv[4:]
            result = command_state(replay, argv[3], with_bytes, [int(a) for a in argv[4:] if a != "--bytes"])
        else:
            result = command_buffer(replay, int(argv[3]), argv[4], argv[5])
    finally:
        replay.close()
    json.dump(result, sys.stdout)
    sys.stdout.write("\n")
    rd.ShutdownReplay()


if __name__ == "__main__":
    try:
        main(sys.argv)
    except Failure as e:
        print(str(e), file=sys.stderr)
        sys.exit(2)
