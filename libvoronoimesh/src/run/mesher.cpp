#include "voronoimesh/run/mesher.hpp"

#include "run/run_job.hpp"

namespace vm {

struct Mesher::State {
  MeshOptions options;
  RunObserver* observer = nullptr;
  size_t meshes = 0;
};

Mesher::Mesher(MeshOptions options, RunObserver* observer) : state_(std::make_unique<State>()) {
  detail::check_options(options);
  detail::parse_pipeline(options); // the passes named must exist, with their parameters in range
  state_->options = std::move(options);
  state_->observer = observer;
}

Mesher::~Mesher() = default;
Mesher::Mesher(Mesher&&) noexcept = default;
Mesher& Mesher::operator=(Mesher&&) noexcept = default;

NodeMesh Mesher::mesh(const Scene& scene) {
  NodeMesh mesh = mesh_scene(scene, state_->options, state_->observer);
  ++state_->meshes;
  return mesh;
}

Scene Mesher::read(const std::string& path, InputOptions input) {
  return read_input(path, detail::input_options_for(std::move(input), state_->options), state_->observer);
}

const MeshOptions& Mesher::options() const { return state_->options; }

size_t Mesher::meshes_made() const { return state_->meshes; }

} // namespace vm
