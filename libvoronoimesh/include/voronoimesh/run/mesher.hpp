#pragma once
/// @file run/mesher.hpp
/// Meshing scene after scene with one set of options: a simulation meshing its
/// evolving interface at every step (the paper's soap-foam use, tens of
/// thousands of meshes per run), or a program meshing a series of volumes.

#include "voronoimesh/run/meshing.hpp"

#include <memory>
#include <string>

namespace vm {

/// Makes one mesh per call, each the one mesh_scene() makes of its scene with
/// the Mesher's options. The options and the pipeline are checked once, when
/// the Mesher is made, so that a typo fails before the first step, not after
/// it. Nothing of one mesh is kept for the next: memory goes back between
/// calls, so a long sequence runs in the memory of its largest step
/// (docs/benchmarks.md, "Sequences": peak memory of 100 steps within 3% of one).
///
/// Not thread-safe: one Mesher per thread.
class Mesher {
public:
  /// @param options  the options of every mesh (the CLI's defaults by default)
  /// @param observer watches every step (stages, iterations, whether to stop); null for none. Not owned.
  /// @throws InvalidOption for an option out of range
  /// @throws InvalidInput  for a pipeline naming an unknown pass or parameter
  explicit Mesher(MeshOptions options = {}, RunObserver* observer = nullptr);
  ~Mesher();
  Mesher(Mesher&&) noexcept;            ///< moves the options, the observer and the count
  Mesher& operator=(Mesher&&) noexcept; ///< moves the options, the observer and the count

  /// The mesh of `scene`: create_mesh() then improve_mesh() with pipeline_for() the scene.
  /// @param scene the scene to mesh; its field must not be null
  /// @return the improved mesh
  /// @throws Error as mesh_scene() throws (Cancelled when the observer asked to stop)
  NodeMesh mesh(const Scene& scene);

  /// The scene of an input file, read as the Mesher's meshes need it (its
  /// top_k and snap), watched by its observer: read_input().
  /// @param path    the input, anything load_input() reads
  /// @param input   how it is read
  /// @return the scene
  /// @throws InvalidInput, IoError as read_input() throws
  Scene read(const std::string& path, InputOptions input = {});

  /// The options every mesh is made with.
  const MeshOptions& options() const;
  /// Meshes made so far.
  size_t meshes_made() const;

private:
  struct State;
  std::unique_ptr<State> state_;
};

} // namespace vm
