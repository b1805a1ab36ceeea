#pragma once
// A participant of a runtime unit test: on shared memory, on a domain of this test process's own
// (the pid spread over 80 domains from `base`), so that tests running at once do not meet.

#include <unistd.h>

#include <string>

#include "teleop/transport/participant_config.h"

namespace teleop::runtime::test {

inline transport::ParticipantConfig local_participant(const std::string& name, int base) {
  transport::ParticipantConfig c;
  c.domain_id = static_cast<int>(getpid() % 80) + base;
  c.name = name;
  c.shm = true;
  return c;
}

}  // namespace teleop::runtime::test
