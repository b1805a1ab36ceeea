/* teleop_device_v1: the C interface of a leader device plugin (docs/devices/plugins.md).
 *
 * A vendor's haptic device (Force Dimension, Haply, 3D Systems Touch, Novint Falcon) whose SDK
 * cannot ship with teleop is driven through a shared library that wraps the SDK and exports one
 * symbol, teleop_device_v1_entry, returning the table below. The leader loads it with dlopen from
 * `leader.device: plugin` (`leader.plugin: {library: ..., settings: {...}}`), checks `abi`, opens
 * the device once and then calls read() and write() once per control period on its real-time
 * thread: they must not block, allocate or take unbounded locks. Plain C: any compiler, any
 * language with a C ABI. A new version of the interface is a new symbol (teleop_device_v2_entry);
 * this one never changes. */
#ifndef TELEOP_DEVICE_V1_H
#define TELEOP_DEVICE_V1_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TELEOP_DEVICE_V1 1u
#define TELEOP_DEVICE_MAX_DOF 16u

/* What the device measures: joint angles (a serial arm, a Touch's gimbal) or the pose of its
 * handle (a delta, a Falcon) in the follower's base frame (the plugin turns its own frame). */
enum { TELEOP_DEVICE_JOINTS = 0u, TELEOP_DEVICE_CARTESIAN = 1u };

typedef struct teleop_device_info {
  /* joint devices: the joints (<= TELEOP_DEVICE_MAX_DOF); Cartesian devices: 0 */
  uint32_t joints;
  /* the efforts write() takes: joint devices one torque per joint [N m]; Cartesian devices 3 (a
   * force [N]) or 6 (force, then moment [N m]); 0: the device renders nothing */
  uint32_t feedback_dof;
  /* the device's own largest effort of each, which the leader never exceeds */
  double max_feedback[TELEOP_DEVICE_MAX_DOF];
  /* for the logs and the report: "omega.3 #1234" */
  char name[64];
} teleop_device_info;

typedef struct teleop_device_state {
  /* when it was measured: CLOCK_MONOTONIC [ns] */
  int64_t stamp_ns;
  /* joint devices [rad, rad/s] */
  double q_rad[TELEOP_DEVICE_MAX_DOF];
  double dq_radps[TELEOP_DEVICE_MAX_DOF];
  /* Cartesian devices: the handle about where it started, base frame [m; quaternion; m/s, rad/s] */
  double position_m[3];
  double orientation_wxyz[4];
  double twist[6];
  /* bit k: button k held (leader.buttons says what each does) */
  uint32_t buttons;
} teleop_device_state;

/* the plugin's own state, opaque to the leader */
typedef struct teleop_device teleop_device;

typedef struct teleop_device_v1 {
  /* TELEOP_DEVICE_V1 */
  uint32_t abi;
  /* TELEOP_DEVICE_JOINTS or TELEOP_DEVICE_CARTESIAN */
  uint32_t kind;
  /* Opens the device with the settings of `leader.plugin.settings` (count pairs of text) for a
   * loop of period_s, and fills info. NULL when it fails: last_error(NULL) says why. */
  teleop_device* (*open)(const char* const* keys, const char* const* values, uint32_t count, double period_s,
                         teleop_device_info* info);
  /* One period's measurement into state. 0: read; otherwise last_error(device) says why, and the
   * leader holds its command until a read succeeds again. Real-time safe. */
  int (*read)(teleop_device* device, teleop_device_state* state);
  /* Renders `count` efforts (info.feedback_dof) for the next period. 0: accepted. Real-time safe. */
  int (*write)(teleop_device* device, const double* effort, uint32_t count);
  /* The last failure, for the logs; device NULL: the last open()'s. Never NULL. */
  const char* (*last_error)(const teleop_device* device);
  /* Stops rendering and releases the device. */
  void (*close)(teleop_device* device);
} teleop_device_v1;

/* The plugin's one exported symbol. */
typedef const teleop_device_v1* (*teleop_device_v1_entry_fn)(void);
#define TELEOP_DEVICE_V1_ENTRY "teleop_device_v1_entry"

#ifdef __cplusplus
}
#endif

#endif /* TELEOP_DEVICE_V1_H */
