// The wire between the gblens layer (app/layer, inside the application) and the receiver
// (views/live/live.h, in gblens): a local SOCK_SEQPACKET socket carrying one JSON message per
// packet, and a shared-memory file (memfd, passed with SCM_RIGHTS) that holds one frame's texels.
// Compiled into both; no Vulkan here. docs/attach.md describes the messages.
#pragma once
#include <cstdint>
#include <string>

namespace gb::wire {

constexpr const char* kSocketEnv = "GBLENS_LIVE_SOCKET";  // set by the receiver for the application
constexpr const char* kLayerName = "VK_LAYER_GBLENS_live";
// The layer is an implicit layer (so that enabling it makes no loader warning in the application's
// debug messenger, as VK_INSTANCE_LAYERS would): found through XDG_DATA_DIRS, enabled by this variable.
constexpr const char* kLayerManifest = "vulkan/implicit_layer.d/VkLayer_gblens_live.json";
constexpr const char* kEnableEnv = "ENABLE_GBLENS_LIVE";
// 2: the request's "only" (Nth streamed frame) became "only_frame" (the application's frame);
// 3: a frame's targets carry "samples" and "sample_stride" (planes per sample), the request
// "ring_off_thread", live picks "subpass" and "attachment"; 4: the request's "last_frame" (with
// "only_frame": the frames only_frame..last_frame, every one); 5: each pass of the passes message
// carries "storage_after" (the storage images the dispatches after it bind).
constexpr int kVersion = 5;

// Message "type" values. Layer -> receiver: hello, report, passes, buffer (a shared-memory file to
// map, sent with its descriptor: id 0 the layer's copy of a frame, others ring buffers read in
// place), retire (a ring buffer gone), frame, nomatch. Receiver -> layer: request, ack (the frame's
// memory is the layer's again), detach (go idle for good).
constexpr const char* kHello = "hello";
constexpr const char* kBuffer = "buffer";
constexpr const char* kRetire = "retire";
constexpr const char* kReport = "report";
constexpr const char* kPasses = "passes";
constexpr const char* kFrame = "frame";
constexpr const char* kNoMatch = "nomatch";
constexpr const char* kRequest = "request";
constexpr const char* kAck = "ack";
constexpr const char* kDetach = "detach";
constexpr const char* kReady = "ready";  // a paced receiver (request "paced"): copy the next frame for it

// Sends one message, with a file descriptor when fd >= 0. Never raises SIGPIPE; false when the
// peer is gone (or the message does not fit a packet).
bool send(int socket, const std::string& json, int fd = -1);

enum class Received { Message, Nothing, Closed };
// Receives one message waiting at most timeoutMs (0: do not wait, -1: wait for one). A file
// descriptor sent with it lands in *fd (else -1; close it when done).
Received receive(int socket, std::string& json, int* fd, int timeoutMs);

// Texels in the shared memory are 16-byte aligned.
constexpr uint64_t alignUp(uint64_t v, uint64_t a = 16) { return (v + a - 1) / a * a; }

// CLOCK_MONOTONIC in nanoseconds: the same clock in both processes (frame-end to receipt latency).
uint64_t monotonicNs();

}  // namespace gb::wire
