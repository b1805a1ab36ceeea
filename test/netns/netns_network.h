#pragma once
// A small network of "hosts" on one machine: one network namespace per host, joined to a bridge
// in the root namespace by a veth pair each. Lets process-level tests run nodes on separate
// network stacks (own addresses, own interfaces, a link that can be cut) without VMs.

#include <string>
#include <vector>

namespace teleop::test {

/// Full path of a system program (the process helpers exec paths, not names); throws when missing.
std::string system_tool(const std::string& name);

/// Why network namespaces cannot be used by this process ("" when they can): not root, or the
/// kernel/iproute2 refuses a namespace, veth pair or bridge.
std::string netns_unavailable_reason();

/// Hosts 0..n-1 with addresses 10.200.0.1.. /24 on interface eth0, loopback up and a default
/// route on eth0 (so multicast has a way out). Names carry this process's pid and a counter, so
/// consecutive and concurrent runs never collide; everything is deleted in the destructor, and
/// leftovers of crashed runs (their pid gone) when the next network is built.
class NetnsNetwork {
 public:
  /// Builds the network. Throws std::runtime_error with iproute2's message on failure.
  explicit NetnsNetwork(int hosts);
  ~NetnsNetwork();
  NetnsNetwork(const NetnsNetwork&) = delete;
  NetnsNetwork& operator=(const NetnsNetwork&) = delete;

  int hosts() const { return hosts_; }
  /// The bridge all hosts are connected to (capture traffic here).
  std::string bridge() const { return tag_ + "br"; }
  std::string host_namespace(int host) const;
  /// The host's IPv4 address.
  std::string address(int host) const;
  /// `argv` run inside the host's namespace (`ip netns exec`).
  std::vector<std::string> on_host(int host, const std::vector<std::string>& argv) const;
  /// Cuts (false) or restores (true) the host's link: its port on the bridge goes down / up.
  void set_link_up(int host, bool up);
  /// Makes the network forbid multicast: the bridge no longer forwards it to any port.
  void block_multicast();

 private:
  std::string port(int host) const { return tag_ + "v" + std::to_string(host); }
  void add_host(int host);
  void remove_all() noexcept;

  std::string tag_;
  int hosts_ = 0;
};

}  // namespace teleop::test
