// enet_transport.cpp — the ENet mesh (see enet_transport.h).
#include "tools/net/enet_transport.h"

#include <enet/enet.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>

#include "fixed/splitmix64.h"

namespace tandem::net {

namespace {

Status bad(const std::string& m) { return Status{StatusCode::invalid_argument, m}; }

bool enet_ready() {
  static std::once_flag once;
  static bool ok = false;
  std::call_once(once, [] {
    ok = enet_initialize() == 0;
    if (ok) std::atexit(enet_deinitialize);
  });
  return ok;
}

constexpr uint8_t k_channel_inputs = 0;
constexpr uint8_t k_channel_control = 1;

}  // namespace

Status parse_address(const std::string& text, Address* out) {
  const size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) {
    return bad("address \"" + text + "\": expected HOST:PORT");
  }
  const std::string port = text.substr(colon + 1);
  if (port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos) {
    return bad("address \"" + text + "\": port \"" + port + "\" is not a number 0…65535");
  }
  const unsigned long p = std::stoul(port);
  if (p > 65535) return bad("address \"" + text + "\": port " + port + " is above 65535");
  out->host = text.substr(0, colon);
  out->port = static_cast<uint16_t>(p);
  return {};
}

EnetTransport::~EnetTransport() { close(0); }

Status EnetTransport::open(const Address& bind, uint32_t local, uint32_t endpoint_count, const Conditions& conditions) {
  if (host_ != nullptr) return bad("transport already open");
  if (!enet_ready()) return bad("enet_initialize failed");
  if (endpoint_count < 2 || endpoint_count > 16) return bad("endpoint count " + std::to_string(endpoint_count) + ", expected 2…16");
  if (local >= endpoint_count) return bad("local endpoint " + std::to_string(local) + ", expected 0…" + std::to_string(endpoint_count - 1));
  ENetAddress address{};
  if (enet_address_set_host_ip(&address, bind.host.c_str()) != 0 && enet_address_set_host(&address, bind.host.c_str()) != 0) {
    return bad("cannot resolve bind host \"" + bind.host + "\"");
  }
  address.port = bind.port;
  host_ = enet_host_create(&address, endpoint_count + 4, 2, 0, 0);
  if (host_ == nullptr) return bad("cannot bind " + bind.host + ":" + std::to_string(bind.port) + " (in use?)");
  local_ = local;
  count_ = endpoint_count;
  conditions_ = conditions;
  rng_ = conditions.seed ^ (uint64_t{local} * 0x9E3779B97F4A7C15ull);
  peers_.assign(endpoint_count, nullptr);
  connected_.assign(endpoint_count, 0);
  delayed_.clear();
  stats_ = {};
  return {};
}

uint16_t EnetTransport::local_port() const {
  if (host_ == nullptr) return 0;
  ENetAddress a{};
  if (enet_socket_get_address(host_->socket, &a) != 0) return 0;
  return a.port;
}

Status EnetTransport::connect_all(const std::vector<Address>& addresses, uint32_t timeout_ms) {
  if (host_ == nullptr) return bad("transport not open");
  if (addresses.size() != count_) {
    return bad(std::to_string(addresses.size()) + " addresses for " + std::to_string(count_) + " endpoints");
  }
  for (uint32_t e = 0; e < local_; ++e) {
    ENetAddress a{};
    if (enet_address_set_host_ip(&a, addresses[e].host.c_str()) != 0 &&
        enet_address_set_host(&a, addresses[e].host.c_str()) != 0) {
      return bad("cannot resolve endpoint " + std::to_string(e) + " host \"" + addresses[e].host + "\"");
    }
    a.port = addresses[e].port;
    ENetPeer* p = enet_host_connect(host_, &a, 2, local_);
    if (p == nullptr) return bad("no ENet peer slot for endpoint " + std::to_string(e));
    p->data = reinterpret_cast<void*>(static_cast<uintptr_t>(e) + 1);
    peers_[e] = p;
  }
  const auto deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  auto all = [&] {
    for (uint32_t e = 0; e < count_; ++e) {
      if (e != local_ && connected_[e] == 0) return false;
    }
    return true;
  };
  while (!all()) {
    if (Clock::now() >= deadline) {
      std::string missing;
      for (uint32_t e = 0; e < count_; ++e) {
        if (e != local_ && connected_[e] == 0) missing += (missing.empty() ? "" : ", ") + std::to_string(e);
      }
      return bad("endpoint " + std::to_string(local_) + ": not connected to endpoint(s) " + missing + " after " +
                 std::to_string(timeout_ms) + " ms");
    }
    poll(10, {}, {});
  }
  return {};
}

uint32_t EnetTransport::draw(uint32_t n) { return n == 0 ? 0 : static_cast<uint32_t>(splitmix64_next(&rng_) % n); }

void EnetTransport::send(uint32_t endpoint, std::span<const uint8_t> packet) {
  if (host_ == nullptr || endpoint >= count_ || connected_[endpoint] == 0) return;
  const bool reliable = packet.size() > 3 && packet[3] != 1;  // everything but input packets
  int copies = 1;
  if (!reliable) {
    if (draw(1000) < conditions_.loss_per_mille) {
      ++stats_.packets_dropped;
      return;
    }
    if (draw(1000) < conditions_.duplicate_per_mille) copies = 2;
  }
  for (int i = 0; i < copies; ++i) {
    const uint32_t delay = conditions_.latency_ms + draw(conditions_.jitter_ms + 1);
    if (delay == 0) {
      transmit(endpoint, reliable, packet);
    } else {
      delayed_.push_back(Delayed{Clock::now() + std::chrono::milliseconds(delay), order_++, endpoint, reliable,
                                 std::vector<uint8_t>(packet.begin(), packet.end())});
    }
  }
}

void EnetTransport::transmit(uint32_t endpoint, bool reliable, std::span<const uint8_t> bytes) {
  ENetPeer* p = peers_[endpoint];
  if (p == nullptr || connected_[endpoint] == 0) return;
  ENetPacket* packet = enet_packet_create(bytes.data(), bytes.size(), reliable ? ENET_PACKET_FLAG_RELIABLE : 0);
  if (packet == nullptr) return;
  if (enet_peer_send(p, reliable ? k_channel_control : k_channel_inputs, packet) != 0) {
    enet_packet_destroy(packet);
    return;
  }
  ++stats_.packets_sent;
  stats_.bytes_sent += bytes.size();
}

void EnetTransport::release_due() {
  if (delayed_.empty()) return;
  const auto now = Clock::now();
  std::vector<Delayed> due;
  auto it = std::stable_partition(delayed_.begin(), delayed_.end(), [&](const Delayed& d) { return d.at > now; });
  due.assign(std::make_move_iterator(it), std::make_move_iterator(delayed_.end()));
  delayed_.erase(it, delayed_.end());
  std::sort(due.begin(), due.end(), [](const Delayed& a, const Delayed& b) { return a.at != b.at ? a.at < b.at : a.order < b.order; });
  for (const Delayed& d : due) transmit(d.endpoint, d.reliable, d.bytes);
}

void EnetTransport::handle_event(void* raw, const std::function<void(uint32_t, std::span<const uint8_t>)>& on_packet,
                                 const std::function<void(uint32_t)>& on_disconnect) {
  ENetEvent& ev = *static_cast<ENetEvent*>(raw);
  switch (ev.type) {
    case ENET_EVENT_TYPE_CONNECT: {
      uint32_t e = UINT32_MAX;
      if (ev.peer->data != nullptr) {
        e = static_cast<uint32_t>(reinterpret_cast<uintptr_t>(ev.peer->data) - 1);  // we connected
      } else if (ev.data < count_ && ev.data != local_ && ev.data > local_ && connected_[ev.data] == 0) {
        e = ev.data;  // they connected: only higher endpoints connect to us
        ev.peer->data = reinterpret_cast<void*>(static_cast<uintptr_t>(e) + 1);
        peers_[e] = ev.peer;
      }
      if (e == UINT32_MAX) {
        ++stats_.connections_refused;
        enet_peer_reset(ev.peer);
        break;
      }
      connected_[e] = 1;
      enet_peer_timeout(ev.peer, 0, 2000, 3000);
      break;
    }
    case ENET_EVENT_TYPE_RECEIVE: {
      if (ev.peer->data != nullptr) {
        const uint32_t e = static_cast<uint32_t>(reinterpret_cast<uintptr_t>(ev.peer->data) - 1);
        ++stats_.packets_received;
        stats_.bytes_received += ev.packet->dataLength;
        if (on_packet) on_packet(e, std::span<const uint8_t>(ev.packet->data, ev.packet->dataLength));
      }
      enet_packet_destroy(ev.packet);
      break;
    }
    case ENET_EVENT_TYPE_DISCONNECT: {
      if (ev.peer->data != nullptr) {
        const uint32_t e = static_cast<uint32_t>(reinterpret_cast<uintptr_t>(ev.peer->data) - 1);
        connected_[e] = 0;
        peers_[e] = nullptr;
        ev.peer->data = nullptr;
        if (on_disconnect) on_disconnect(e);
      }
      break;
    }
    case ENET_EVENT_TYPE_NONE:
      break;
  }
}

void EnetTransport::poll(uint32_t wait_ms, const std::function<void(uint32_t, std::span<const uint8_t>)>& on_packet,
                         const std::function<void(uint32_t)>& on_disconnect) {
  if (host_ == nullptr) return;
  const auto deadline = Clock::now() + std::chrono::milliseconds(wait_ms);
  for (;;) {
    release_due();
    enet_host_flush(host_);
    const auto now = Clock::now();
    uint32_t wait = 0;
    if (now < deadline) {
      wait = static_cast<uint32_t>(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count());
      if (!delayed_.empty()) wait = std::min<uint32_t>(wait, 1);
    }
    ENetEvent ev;
    const int r = enet_host_service(host_, &ev, wait);
    if (r > 0) {
      handle_event(&ev, on_packet, on_disconnect);
      while (enet_host_check_events(host_, &ev) > 0) handle_event(&ev, on_packet, on_disconnect);
    }
    if (Clock::now() >= deadline) break;
  }
  release_due();
  enet_host_flush(host_);
}

void EnetTransport::close(uint32_t linger_ms) {
  if (host_ == nullptr) return;
  if (linger_ms != 0) {
    // Let delayed packets leave, then disconnect politely.
    const auto deadline = Clock::now() + std::chrono::milliseconds(linger_ms);
    while (!delayed_.empty() && Clock::now() < deadline) poll(5, {}, {});
    for (uint32_t e = 0; e < count_; ++e) {
      if (peers_[e] != nullptr && connected_[e] != 0) enet_peer_disconnect_later(peers_[e], 0);
    }
    ENetEvent ev;
    while (Clock::now() < deadline && enet_host_service(host_, &ev, 5) >= 0) {
      if (ev.type == ENET_EVENT_TYPE_RECEIVE) enet_packet_destroy(ev.packet);
      bool any = false;
      for (uint32_t e = 0; e < count_; ++e) any = any || (peers_[e] != nullptr && peers_[e]->state != ENET_PEER_STATE_DISCONNECTED);
      if (!any) break;
    }
  }
  enet_host_destroy(host_);
  host_ = nullptr;
  peers_.assign(count_, nullptr);
  connected_.assign(count_, 0);
  delayed_.clear();
}

}  // namespace tandem::net
