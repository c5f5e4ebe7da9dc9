// The layer's side of the wire (internal to app/layer): the thread's state, shared by stream.cpp
// (connection, thread, messages) and send.cpp (a finished frame to the receiver).
#pragma once
#include <nlohmann/json.hpp>

#include "app/layer/layer.h"

namespace gbl {

struct Stream {
  DeviceData* d = nullptr;
  int socket = -1, wake = -1;
  std::thread thread;
  std::atomic<bool> stop{false};
  std::mutex lock;  // pending, outbox, reported
  std::deque<std::unique_ptr<PendingFrame>> pending;
  std::vector<std::string> outbox;
  std::set<std::string> reported;
  // The thread's own:
  int shm = -1;                  // buffer 0: a frame copied out of the ring (when the ring is not shared)
  uint8_t* map = nullptr;
  size_t mapSize = 0;
  bool shmSent = false, receiverBusy = false;
  std::set<uint32_t> sentBuffers;              // shared ring buffers the receiver has mapped
  std::unique_ptr<PendingFrame> atReceiver;    // the frame the receiver reads in place (its buffers held)
  std::unique_ptr<PendingFrame> waiting;       // done, to be sent at the receiver's ack (the newest such)
  uint64_t sent = 0, dropped = 0, torn = 0;
  double copyMs = 0.0;
  double downloadMs = 0.0;  // of which the staged ring's downloads on the layer's queue
  std::shared_ptr<const Request> request;  // as the receiver sent it (to the device at startStream)
};

// send.cpp
// A finished frame: sent if the receiver is free and the ring was not written again meanwhile,
// else dropped (counted).
void process(Stream& st, std::unique_ptr<PendingFrame> f);
// A paced request's granted frame that will not be sent: its grant goes back (DeviceData::grants).
void giveBack(DeviceData& d, const PendingFrame& f);
nlohmann::json statsJson(Stream& st);

// stream.cpp
void goIdle(Stream& st);  // the receiver went away or detached: stop copying for good
// Queues a message for the thread to send, once per key.
void sendOnce(DeviceData& d, const std::string& key, const std::string& message);

}  // namespace gbl
