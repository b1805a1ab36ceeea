/* The reference plugin of teleop_device_v1 (teleop/leader/teleop_device_v1.h): a simulated 3-DoF
 * delta-class haptic device, written as a vendor's plugin would be, in C against the header only.
 *
 * Its handle is a point mass in a cube of the base frame. A simulated operator's hand holds it
 * through a spring-damper and moves along a script: out to `reach_*_m` over `ramp_s`, plus a sine
 * of `amplitude_*_m` at `frequency_hz`. The force the leader renders acts on the mass, so the
 * hand feels it and gives way to it as a real operator's would:
 *   m dv/dt = K (target - p) - D v - c v + F_rendered,  p kept inside the cube by its end stops,
 * c the mechanism's own viscous friction. From let_go_at_s on the hand is off: no K, no D, no
 * button held, only the rendered force and the friction act on the handle.
 * Settings (leader.plugin.settings): mass_kg, hand_stiffness_n_per_m, hand_damping_ns_per_m,
 * friction_ns_per_m, reach_{x,y,z}_m, ramp_s, amplitude_{x,y,z}_m, frequency_hz, half_side_m,
 * max_force_n, buttons, let_go_at_s; and to test the leader's handling of a failing device:
 * fail_after_reads, nan_after_reads, and crash_after_reads (a vendor SDK that crashes: SIGSEGV). */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "teleop/leader/teleop_device_v1.h"

struct teleop_device {
  double period_s;
  double mass_kg, stiffness, damping, friction, reach[3], ramp_s, amplitude[3], frequency_hz, half_side_m, max_force_n;
  double let_go_at_s;
  long fail_after_reads, nan_after_reads, crash_after_reads;
  uint32_t buttons;
  long reads;
  double p[3], v[3], force[3];
  char error[160];
};

static char open_error[160] = "no error";

static int64_t now_ns(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (int64_t)t.tv_sec * 1000000000 + t.tv_nsec;
}

/* the setting `key` into the field it names; 0 when there is none */
static int set(struct teleop_device* d, const char* key, double value) {
  struct { const char* key; double* field; } doubles[] = {
      {"mass_kg", &d->mass_kg}, {"hand_stiffness_n_per_m", &d->stiffness}, {"hand_damping_ns_per_m", &d->damping},
      {"reach_x_m", &d->reach[0]}, {"reach_y_m", &d->reach[1]}, {"reach_z_m", &d->reach[2]}, {"ramp_s", &d->ramp_s},
      {"amplitude_x_m", &d->amplitude[0]}, {"amplitude_y_m", &d->amplitude[1]}, {"amplitude_z_m", &d->amplitude[2]},
      {"frequency_hz", &d->frequency_hz}, {"half_side_m", &d->half_side_m}, {"max_force_n", &d->max_force_n},
      {"friction_ns_per_m", &d->friction}, {"let_go_at_s", &d->let_go_at_s}};
  for (size_t i = 0; i < sizeof doubles / sizeof doubles[0]; ++i) {
    if (strcmp(key, doubles[i].key) == 0) {
      *doubles[i].field = value;
      return 1;
    }
  }
  if (strcmp(key, "fail_after_reads") == 0) d->fail_after_reads = (long)value;
  else if (strcmp(key, "nan_after_reads") == 0) d->nan_after_reads = (long)value;
  else if (strcmp(key, "crash_after_reads") == 0) d->crash_after_reads = (long)value;
  else if (strcmp(key, "buttons") == 0) d->buttons = (uint32_t)value;
  else return 0;
  return 1;
}

static teleop_device* delta_open(const char* const* keys, const char* const* values, uint32_t count, double period_s,
                                 teleop_device_info* info) {
  struct teleop_device* d = calloc(1, sizeof *d);
  if (d == NULL) return NULL;
  d->period_s = period_s;
  d->mass_kg = 0.3;
  d->stiffness = 400.0;
  d->damping = 12.0;
  d->ramp_s = 1.0;
  d->frequency_hz = 0.2;
  d->half_side_m = 0.08;
  d->max_force_n = 12.0;
  d->friction = 2.0;
  d->let_go_at_s = INFINITY;
  d->buttons = 1u; /* the hand holds the device: its button 0 (a dead-man, if the leader makes it one) */
  for (uint32_t i = 0; i < count; ++i) {
    char* end = NULL;
    const double value = strtod(values[i], &end);
    if (end == values[i] || *end != '\0' || !isfinite(value)) {
      snprintf(open_error, sizeof open_error, "setting %s: '%s' is not a number", keys[i], values[i]);
      free(d);
      return NULL;
    }
    if (!set(d, keys[i], value)) {
      snprintf(open_error, sizeof open_error, "unknown setting %s", keys[i]);
      free(d);
      return NULL;
    }
  }
  if (d->mass_kg <= 0.0 || d->half_side_m <= 0.0 || period_s <= 0.0) {
    snprintf(open_error, sizeof open_error, "mass_kg, half_side_m and the period must be positive");
    free(d);
    return NULL;
  }
  info->joints = 0;
  info->feedback_dof = 3;
  for (int k = 0; k < 3; ++k) info->max_feedback[k] = d->max_force_n;
  snprintf(info->name, sizeof info->name, "simulated delta");
  snprintf(d->error, sizeof d->error, "no error");
  return d;
}

/* where the operator's hand wants the handle at t */
static double target(const struct teleop_device* d, int k, double t) {
  const double ramp = d->ramp_s > 0.0 ? fmin(t / d->ramp_s, 1.0) : 1.0;
  return d->reach[k] * ramp + d->amplitude[k] * sin(2.0 * M_PI * d->frequency_hz * t);
}

static int delta_read(teleop_device* d, teleop_device_state* state) {
  if (d->crash_after_reads > 0 && d->reads >= d->crash_after_reads) raise(SIGSEGV);
  if (d->fail_after_reads > 0 && d->reads >= d->fail_after_reads) {
    snprintf(d->error, sizeof d->error, "lost the device after %ld reads (fail_after_reads)", d->reads);
    return -1;
  }
  const double t = (double)d->reads * d->period_s;
  const int hand_on = t < d->let_go_at_s;
  ++d->reads;
  for (int k = 0; k < 3; ++k) {
    const double hand = hand_on ? d->stiffness * (target(d, k, t) - d->p[k]) - d->damping * d->v[k] : 0.0;
    const double f = hand - d->friction * d->v[k] + d->force[k];
    d->v[k] += f / d->mass_kg * d->period_s;
    d->p[k] += d->v[k] * d->period_s;
    /* the end stops */
    if (fabs(d->p[k]) > d->half_side_m) {
      d->p[k] = copysign(d->half_side_m, d->p[k]);
      d->v[k] = 0.0;
    }
  }
  memset(state, 0, sizeof *state);
  state->stamp_ns = now_ns();
  const int poisoned = d->nan_after_reads > 0 && d->reads > d->nan_after_reads;
  for (int k = 0; k < 3; ++k) {
    state->position_m[k] = poisoned ? NAN : d->p[k];
    state->twist[k] = d->v[k];
  }
  state->orientation_wxyz[0] = 1.0;
  state->buttons = hand_on ? d->buttons : 0u;
  return 0;
}

static int delta_write(teleop_device* d, const double* effort, uint32_t count) {
  if (count != 3) {
    snprintf(d->error, sizeof d->error, "write: %u efforts, the device takes 3", count);
    return -1;
  }
  for (int k = 0; k < 3; ++k) {
    if (!isfinite(effort[k])) {
      snprintf(d->error, sizeof d->error, "write: a force that is not finite");
      return -1;
    }
    d->force[k] = fmax(-d->max_force_n, fmin(d->max_force_n, effort[k]));
  }
  return 0;
}

static const char* delta_last_error(const teleop_device* d) { return d != NULL ? d->error : open_error; }

static void delta_close(teleop_device* d) { free(d); }

static const teleop_device_v1 kDelta = {TELEOP_DEVICE_V1, TELEOP_DEVICE_CARTESIAN, delta_open, delta_read, delta_write,
                                        delta_last_error, delta_close};

__attribute__((visibility("default"))) const teleop_device_v1* teleop_device_v1_entry(void) { return &kDelta; }
