#pragma once
// An object in a hand scene (config/models/svh_hand_grasp.xml): a free body the hand is to grasp,
// held in place by a weld equality (its support, as if a person held it out to the hand) until
// release() switches the weld off; from then on only the hand holds it against gravity. Reads
// where the object is and how the hand touches it. docs/hand.md.

#include <mujoco/mujoco.h>

#include <array>
#include <string>

#include "teleop/hand/hand_plant.h"

namespace teleop::hand {

class GraspObject {
 public:
  /// Finds the body `body` (with a free joint) and the weld `support` in the hand's model; the
  /// hand must outlive this. Throws std::out_of_range naming the model and the missing element,
  /// std::runtime_error when the body has no free joint.
  explicit GraspObject(HandPlant& hand, const std::string& body = "object",
                       const std::string& support = "object_support");

  /// The support's weld is active.
  bool supported() const;
  /// Switches the support off (the object now rests on whatever touches it). Real-time safe.
  void release();
  /// Switches the support on again, welding the object where it was at load time (setup).
  void restore();

  /// The object's centre of mass in the world [m] (after the last step).
  std::array<double, 3> position_m() const;
  /// Contacts between the object and any geom of the hand (a body a hand joint moves, or the
  /// palm and the rest of the hand's base: every body below the hand's mount).
  int hand_contacts() const;
  /// Number of hand bodies (fingers' links, palm) touching the object.
  int touching_links() const;
  /// Sum of the normal forces of those contacts [N].
  double hand_contact_force_n() const;
  /// The object's mass [kg].
  double mass_kg() const;

 private:
  bool is_hand_geom(int geom) const;
  /// The hand's body in a contact between the object and the hand; -1 for any other contact.
  int hand_body_touching(const mjContact& c) const;

  HandPlant& hand_;
  int body_ = -1;
  int support_ = -1;
  int hand_root_ = -1;  // the hand's root body (svh_mount): hand geoms are on it or below it
};

}  // namespace teleop::hand
