// teleop_lockstep_controller: the external controller of the twin's lock-step mode (docs/twin.md).
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "teleop/common/version.h"
#include "teleop/runtime/shutdown_signal.h"
#include "lockstep_controller.h"

int main(int argc, char** argv) {
  CLI::App app{"teleop lock-step controller: answers every twin state with one joint impedance command",
               "teleop_lockstep_controller"};
  app.set_version_flag("--version", teleop::version_text());
  teleop::transport::ParticipantConfig transport;
  transport.name = "lockstep_controller";
  teleop::twin::LockstepControllerConfig config;
  app.add_option("--domain", transport.domain_id, "DDS domain id")->check(CLI::Range(0, 232));
  app.add_option("--stall-after", config.stall_after, "stop answering after this many steps (0: never)");
  app.add_option("--amplitude", config.amplitude_rad, "amplitude of the commanded sine [rad]");
  app.add_option("--idle-timeout", config.idle_timeout_s, "exit when no state came for this long [s]");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
  teleop::runtime::install_shutdown_handlers();
  try {
    teleop::transport::Participant participant(transport);
    teleop::twin::LockstepController controller(participant, config);
    const uint64_t sent = controller.run();
    spdlog::info("lockstep_controller: {} commands sent", sent);
    return 0;
  } catch (const std::exception& e) {
    spdlog::error("lockstep_controller: {}", e.what());
    return 1;
  }
}
