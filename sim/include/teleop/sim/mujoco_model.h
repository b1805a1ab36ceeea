#pragma once
// A MuJoCo model and its simulation state, loaded from an MJCF file (config/models/*.xml, see
// docs/models.md), with name lookups that fail loudly.

#include <mujoco/mujoco.h>

#include <memory>
#include <string>
#include <string_view>

namespace teleop::sim {

/// Owns one mjModel and one mjData made for it; both are freed with MuJoCo's own functions.
/// Move-only. Loading and the lookups allocate and throw (setup time); model()/data() do not,
/// and stepping through them (mj_step etc.) is up to the caller.
class MujocoModel {
 public:
  /// Loads and compiles an MJCF file (includes are resolved relative to its directory) and makes
  /// its data. Throws std::runtime_error naming `path` and carrying MuJoCo's error text when the
  /// file is missing, malformed or does not compile.
  static MujocoModel load(const std::string& path);

  MujocoModel(MujocoModel&&) noexcept = default;
  MujocoModel& operator=(MujocoModel&&) noexcept = default;
  MujocoModel(const MujocoModel&) = delete;
  MujocoModel& operator=(const MujocoModel&) = delete;
  ~MujocoModel() = default;

  const mjModel* model() const { return model_.get(); }
  mjModel* model() { return model_.get(); }
  const mjData* data() const { return data_.get(); }
  mjData* data() { return data_.get(); }

  /// The file this was loaded from.
  const std::string& path() const { return path_; }
  /// MuJoCo's warning from loading ("" when there was none).
  const std::string& load_warning() const { return warning_; }

  /// Ids by name. Each throws std::out_of_range naming the model file, the kind and `name` when
  /// the model has no such element.
  int joint_id(std::string_view name) const;
  int site_id(std::string_view name) const;
  int actuator_id(std::string_view name) const;
  int body_id(std::string_view name) const;
  int geom_id(std::string_view name) const;
  int keyframe_id(std::string_view name) const;

  /// Index of a joint's first coordinate in qpos / first DoF in qvel (throws as joint_id).
  int joint_qpos_address(std::string_view name) const;
  int joint_dof_address(std::string_view name) const;

  /// Resets the data to the model's default state (mj_resetData) and recomputes the derived
  /// quantities (mj_forward).
  void reset();
  /// Resets the data to a keyframe (throws as keyframe_id) and recomputes (mj_forward).
  void reset(std::string_view keyframe);

 private:
  struct ModelDeleter {
    void operator()(mjModel* m) const noexcept { mj_deleteModel(m); }
  };
  struct DataDeleter {
    void operator()(mjData* d) const noexcept { mj_deleteData(d); }
  };

  MujocoModel(std::string path, std::unique_ptr<mjModel, ModelDeleter> model, std::unique_ptr<mjData, DataDeleter> data,
              std::string warning);
  int id_of(mjtObj type, const char* kind, std::string_view name) const;

  std::string path_;
  std::unique_ptr<mjModel, ModelDeleter> model_;
  std::unique_ptr<mjData, DataDeleter> data_;
  std::string warning_;
};

}  // namespace teleop::sim
