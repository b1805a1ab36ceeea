#include "teleop/doctor/finding.h"

#include <algorithm>
#include <cstdio>

namespace teleop::doctor {

const char* verdict_name(Verdict verdict) {
  switch (verdict) {
    case Verdict::kOk:
      return "ok";
    case Verdict::kWarn:
      return "warn";
    case Verdict::kFail:
      return "FAIL";
  }
  return "?";
}

std::string findings_text(const std::vector<Finding>& findings) {
  size_t width = 0;
  for (const Finding& f : findings) width = std::max(width, f.check.size());
  std::string text;
  for (const Finding& f : findings) {
    char head[96];
    std::snprintf(head, sizeof(head), "  %-4s  %-*s  ", verdict_name(f.verdict), static_cast<int>(width), f.check.c_str());
    text += head + f.found + "\n";
    if (!f.fix.empty()) text += std::string(8 + width, ' ') + "fix: " + f.fix + "\n";
  }
  return text;
}

int exit_code(const std::vector<Finding>& findings) {
  return std::any_of(findings.begin(), findings.end(), [](const Finding& f) { return f.verdict == Verdict::kFail; })
             ? 1
             : 0;
}

}  // namespace teleop::doctor
