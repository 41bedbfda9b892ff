#pragma once
// Kernel counters of datagrams lost on the way in, for the daemon's status.
#include <cstdint>

namespace mfp {

// Udp RcvbufErrors of /proc/net/snmp (datagrams the kernel dropped because a socket's
// receive buffer was full; every UDP socket of the network namespace); -1 when unreadable.
int64_t ReadUdpReceiveErrors();

// net.core.rmem_max [bytes], the cap on a socket receive buffer; -1 when unreadable.
int64_t ReadRmemMax();

}  // namespace mfp
