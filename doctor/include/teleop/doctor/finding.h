#pragma once
// One verdict of `teleop doctor`: what it checked, what it found, and how to fix a miss.

#include <string>
#include <vector>

namespace teleop::doctor {

enum class Verdict {
  kOk,
  kWarn,  ///< the nodes run, but not as a lab's 1 kHz loop should (jitter, no time sync, ...)
  kFail,  ///< a node the configs describe could not start (realtime: required refused, a CAN bus missing)
};

struct Finding {
  std::string check;  ///< "kernel", "rtprio", "can0", ...
  Verdict verdict = Verdict::kOk;
  std::string found;  ///< what is there, in numbers and names
  std::string fix;    ///< a command or a file to change; empty when nothing is to be done
};

const char* verdict_name(Verdict verdict);

/// The findings as the doctor prints them: one line each, the fix indented below a miss.
std::string findings_text(const std::vector<Finding>& findings);

/// 1 when a finding failed (a configured node could not run here), else 0.
int exit_code(const std::vector<Finding>& findings);

}  // namespace teleop::doctor
