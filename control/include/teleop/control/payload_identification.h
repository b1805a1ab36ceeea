#pragma once
// Payload identification from static poses (docs/calibration.md): at rest the external-torque
// estimate of an arm carrying an unmodelled payload is J(q)^T W(q) (m, m c) + b, linear in the
// payload's mass m, its first moment m c and a constant bias b per joint. A least-squares fit over
// poses that turn the flange through gravity recovers all eleven.

#include <vector>

#include "teleop/control/arm_dynamics.h"
#include "teleop/control/payload.h"
#include "teleop/control/types.h"

namespace teleop::control {

/// One pose at rest and the external torque estimated there (averaged over a while).
struct PayloadSample {
  JointVector q = JointVector::Zero();
  JointVector tau_ext_nm = JointVector::Zero();
};

struct PayloadFit {
  ArmCalibration calibration;
  /// RMS of what the fit leaves unexplained, over every joint of every pose [Nm].
  double residual_rms_nm = 0.0;
  /// Smallest over largest singular value of the regressor: near 0, the poses cannot tell the
  /// parameters apart (too few, or too alike).
  double conditioning = 0.0;
};

/// Fits the payload and the bias to `samples` (at least 2) on `dynamics`' model, the arm's
/// model without the payload. Throws std::invalid_argument for fewer than 2 samples or poses that
/// leave the mass or the centre of mass undetermined. Setup time: allocates.
PayloadFit identify_payload(ArmDynamics& dynamics, const std::vector<PayloadSample>& samples);

}  // namespace teleop::control
