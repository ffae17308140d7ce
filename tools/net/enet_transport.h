// enet_transport.h — UDP transport for replay/session.h over ENet (Debian
// libenet-dev), with an optional network conditions simulator (seeded loss,
// latency, jitter, duplication; jitter reorders) on the sending side.
//
// TOPOLOGY: a full mesh. Endpoint e binds its own address (port 0: any free
// port, see local_port()) and connects to every endpoint with a lower index;
// the higher ones connect to it. The connect request's 32-bit data carries
// the connecting endpoint's index, so every ENet peer maps to one endpoint;
// a connection claiming an out-of-range index, this endpoint's own, or one
// already connected is refused and counted.
//
// CHANNELS: session input packets (type byte 1) go unreliable on channel 0
// (they carry the last ticks' inputs and hashes redundantly); every other
// packet (desync notices, body hashes) goes reliable on channel 1. Loss
// simulation applies to channel 0 only; latency and jitter to both.
//
// Tools only: uses the system clock and sockets; nothing here reaches the
// simulation except through Session::receive.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "physics/tandem.h"

typedef struct _ENetHost ENetHost;
typedef struct _ENetPeer ENetPeer;

namespace tandem::net {

/// Conditions added to every packet sent (0: none).
struct Conditions {
  uint64_t seed = 1;
  uint32_t loss_per_mille = 0;       ///< unreliable packets dropped, ‰
  uint32_t duplicate_per_mille = 0;  ///< unreliable packets sent twice, ‰
  uint32_t latency_ms = 0;           ///< added one-way delay
  uint32_t jitter_ms = 0;            ///< plus uniform 0…jitter_ms (reorders)
};

/// One endpoint's address: "127.0.0.1:7000" (port 0 when binding: any).
struct Address {
  std::string host = "127.0.0.1";
  uint16_t port = 0;
};

/// Parses "HOST:PORT"; the message names the text on failure.
Status parse_address(const std::string& text, Address* out);

/// Counters of one transport.
struct TransportStats {
  uint64_t packets_sent = 0, bytes_sent = 0, packets_dropped = 0;
  uint64_t packets_received = 0, bytes_received = 0;
  uint64_t connections_refused = 0;
};

/// The ENet mesh of one endpoint (see the file comment).
class EnetTransport {
 public:
  EnetTransport() = default;
  ~EnetTransport();
  EnetTransport(const EnetTransport&) = delete;
  EnetTransport& operator=(const EnetTransport&) = delete;

  /// Binds `bind` for endpoint `local` of `endpoint_count` (2…16).
  Status open(const Address& bind, uint32_t local, uint32_t endpoint_count, const Conditions& conditions = {});
  /// The port actually bound (after open).
  uint16_t local_port() const;
  /// Connects to every endpoint (addresses[e] for e < local; the others
  /// connect here) and waits until all are connected or `timeout_ms` passed;
  /// the message then lists the endpoints still missing.
  Status connect_all(const std::vector<Address>& addresses, uint32_t timeout_ms);
  /// Sends a session packet to `endpoint` (queued while the conditions delay it).
  void send(uint32_t endpoint, std::span<const uint8_t> packet);
  /// Services the socket for up to `wait_ms`, releasing delayed packets and
  /// delivering received ones to on_packet(from, bytes); on_disconnect(e) when
  /// an endpoint's connection ends.
  void poll(uint32_t wait_ms, const std::function<void(uint32_t, std::span<const uint8_t>)>& on_packet,
            const std::function<void(uint32_t)>& on_disconnect);
  /// Disconnects from everyone (flushes pending packets first, up to `linger_ms`).
  void close(uint32_t linger_ms = 200);
  const TransportStats& stats() const { return stats_; }

 private:
  using Clock = std::chrono::steady_clock;
  struct Delayed {
    Clock::time_point at;
    uint64_t order;
    uint32_t endpoint;
    bool reliable;
    std::vector<uint8_t> bytes;
  };
  void release_due();
  void transmit(uint32_t endpoint, bool reliable, std::span<const uint8_t> bytes);
  void handle_event(void* event, const std::function<void(uint32_t, std::span<const uint8_t>)>& on_packet,
                    const std::function<void(uint32_t)>& on_disconnect);
  uint32_t draw(uint32_t n);

  ENetHost* host_ = nullptr;
  uint32_t local_ = 0;
  uint32_t count_ = 0;
  Conditions conditions_;
  uint64_t rng_ = 0;
  uint64_t order_ = 0;
  std::vector<ENetPeer*> peers_;      // per endpoint, null until connected
  std::vector<uint8_t> connected_;
  std::vector<Delayed> delayed_;
  TransportStats stats_;
};

}  // namespace tandem::net
