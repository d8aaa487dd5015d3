#pragma once
/// @file run/meshing.hpp
/// The one run path of voronoimesh, from an input to the files written: read
/// the input and make its phase functions, sample them and create the initial
/// mesh (paper sect. 4.1), improve it with a pipeline of passes (paper
/// Algorithm 1), check it and write it. run_job() does all of it, as the CLI's
/// commands do (they only translate their options into a MeshJob); the stages
/// are here too for programs that have their own data or want the mesh between
/// stages: read_input(), create_mesh(), improve_mesh(), write_outputs().
///
/// A RunObserver watches any of them: which stage runs, what each did, every
/// iteration, and whether to stop.
///
/// Scenes come from files (read_input(), load_input() in fields/input.hpp),
/// from arrays in memory (fields/array_input.hpp), from closed forms
/// (parse_scene(), fields/scene.hpp) or from any PhaseField of your own:
/// Scene{grid, field}.

#include "voronoimesh/check/label_agreement.hpp"
#include "voronoimesh/create/create.hpp"
#include "voronoimesh/fields/input.hpp"
#include "voronoimesh/fields/scene.hpp"
#include "voronoimesh/improve/offsets.hpp"
#include "voronoimesh/improve/pipeline.hpp"
#include "voronoimesh/improve/registry.hpp"
#include "voronoimesh/mesh/node_mesh.hpp"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vm {

/// Options of create_mesh(), improve_mesh() and run_job(); the defaults are
/// the CLI's. An option out of range throws InvalidOption naming it.
struct MeshOptions {
  // --- create ---------------------------------------------------------------
  /// Grid cells per axis, each in [1, 4096]; none keeps the scene's grid.
  /// The domain stays the scene's. Finer grids resolve thinner features; time
  /// and memory grow with the cube.
  std::optional<std::array<int, 3>> grid;
  /// Background tetrahedra (create/create.hpp); bcc rounds each cell count up
  /// to even. None: the scene's (lattice_for()), bcc but for label volumes
  /// read voxel-faithful (InputOptions::voxel_faithful) with structures one
  /// voxel thin where bcc has no node.
  std::optional<Lattice> lattice;
  /// Snapping threshold in grid spacings, in [0, 0.5] (paper sect. 4.1: 0.2).
  double snap = 0.2;
  /// Phases kept per grid node when sampling (and per voxel when reading a
  /// volume), in [1, 16] (fields/sampled_field.hpp).
  int top_k = 4;
  /// Close the domain: box faces become surfaces against an extra phase
  /// "exterior", so every phase is a closed volume (NodeMesh::outside_phase).
  bool close = false;
  /// Check the created and the improved mesh (check/validate.hpp) and throw
  /// TopologyError if one fails. Off saves a linear-time check. A mesh read
  /// from a file to be improved is always checked.
  bool validate = true;

  // --- improve --------------------------------------------------------------
  /// Iterations of the pipeline, 0 or more; 0 leaves the initial mesh as created.
  int iterations = 20;
  /// Passes per iteration, "name,name:key=value,..." (improve/pipeline.hpp).
  /// Empty: the input's default (pipeline_for()): the paper's smoothing,
  /// projection, clamping and flipping, after remeshing for label volumes.
  std::string pipeline;
  /// Target edge length in world units, 0 for none: the default pipeline is
  /// then remesh:length=`size` and kPassesAfterRemesh for every input (the
  /// same target for a mesh read back from a file). Not with `pipeline` (give
  /// remesh:length=L there). With `tolerance`, the longest target edge.
  double size = 0;
  /// With `size`: how far, in world units, a triangle may stand off a curved
  /// surface (like CGAL's facet distance); edges shorten where surfaces curve,
  /// down to `min_size` (remesh:tolerance). 0: edges of `size` everywhere.
  double tolerance = 0;
  /// With `tolerance`: the shortest target edge, in world units, between a
  /// tenth of `size` and `size`; 0: half of `size` (remesh:min_size).
  double min_size = 0;
  /// The passes `pipeline` may name (e.g. built-ins plus a plugin's); null:
  /// the built-in passes. Not owned; must outlive the call.
  const PassRegistry* passes = nullptr;
  /// Stop early once quality stops improving (RunOptions::stop_when_converged),
  /// `iterations` then being the most. Unset: the input's default, on for label
  /// volumes meshed with their default pipeline (kLabelVolumePipeline in one
  /// process, the paper's under mpi::run_job(): their worst triangle settles
  /// within ten iterations or so, and the rest only raise the mean by about
  /// 0.001 each), off otherwise.
  std::optional<bool> stop_when_converged;
  /// Undo moves and flips that make surfaces cross (improve/guard.hpp).
  bool guard_crossings = true;
  /// Look for crossings once every this many iterations, at least 1
  /// (RunOptions::check_crossings_every); 1 with a quality history (whose
  /// iterations must not run twice) and in a distributed run.
  int check_crossings_every = 1;

  // --- both -----------------------------------------------------------------
  /// Worker threads, 0 or more; 0 = all cores. Results do not depend on it.
  int threads = 0;
};

/// The stages of a run, in the order they come.
enum class Stage {
  read,    ///< reading the input (or the mesh to improve) and making the phase functions
  sample,  ///< sampling the phase functions on the grid
  create,  ///< creating the initial mesh
  improve, ///< the improvement iterations
  write,   ///< writing the outputs
};

/// What create_mesh() did.
struct CreateReport {
  GridSpec grid;                   ///< the grid sampled (the lattice's, create_grid())
  Lattice lattice = Lattice::bcc;  ///< the background tetrahedra
  /// Nodes of the initial mesh.
  size_t nodes = 0, triangles = 0; ///< triangles of the initial mesh
  double sampling_seconds = 0;     ///< sampling the phase functions on the grid
  CreateStats stats;               ///< create itself (create/create.hpp)
  /// Phases of the input with no triangle in the mesh: smaller or thinner than
  /// the lattice resolves (each is also told as a RunObserver::note()).
  std::vector<int32_t> lost_phases;
};

/// What improve_mesh() did.
struct ImproveReport {
  std::string pipeline;  ///< the pipeline run, as given
  int iterations = 0;    ///< iterations done (fewer than asked when stopped early)
  bool converged = false; ///< stopped before the iterations asked for because quality stopped improving
  double seconds = 0;    ///< wall time of the iterations
  /// Minimum triangle quality q (triangle_quality()) before the first iteration.
  double initial_min_quality = 0, initial_mean_quality = 0; ///< mean q before the first iteration
  /// Minimum triangle quality q after the last iteration.
  double min_quality = 0, mean_quality = 0;                 ///< mean q after the last iteration
};

/// Watches a run: progress, what each stage did, and whether to stop. Every
/// method does nothing (or says "go on") unless overridden; all are called on
/// the thread that runs the job.
class RunObserver {
public:
  virtual ~RunObserver() = default;
  /// A stage begins.
  /// @param stage the stage beginning
  /// @param what  the stage in a few words ("sampling 274625 grid nodes")
  virtual void stage(Stage stage, const std::string& what);
  /// The input at `path` was read and its phase functions made in `seconds`.
  /// Not called for the built-in demo scene.
  /// @param path    the input read
  /// @param scene   the scene made from it
  /// @param seconds wall time of reading it and making its phase functions
  virtual void input_read(const std::string& path, const Scene& scene, double seconds);
  /// The initial mesh was created.
  /// @param report what create_mesh() did
  virtual void created(const CreateReport& report);
  /// After each improvement iteration, and with iteration 0 before the first
  /// (Pipeline::run()'s observer).
  /// @param report what the iteration did (iteration 0: the initial mesh)
  /// @param mesh   the mesh after it
  virtual void iteration(const IterationReport& report, const InterfaceMesh& mesh);
  /// Improvement ended.
  /// @param report what improve_mesh() did
  virtual void improved(const ImproveReport& report);
  /// The outputs were written: the mesh files (one, or one per phase pair for
  /// .stl) and the per-phase STL files.
  /// @param mesh_files  the mesh files written (empty when RunOutputs::mesh is)
  /// @param phase_files the per-phase STL files written (empty when RunOutputs::per_phase is)
  virtual void written(const std::vector<std::string>& mesh_files, const std::vector<std::string>& phase_files);
  /// A line worth telling the user that is neither progress nor an error.
  /// @param line the line
  virtual void note(const std::string& line);
  /// Asked between stages and before every iteration: true stops the run,
  /// which then throws Cancelled having written nothing.
  /// @return true to stop the run; the default returns false
  virtual bool stop_requested();
};

/// The files a run writes; an empty path writes nothing of that kind.
struct RunOutputs {
  /// The mesh, in the format of its extension (io/write_mesh.hpp).
  std::string mesh;
  /// A folder (made if missing) of one closed STL per phase (io::write_per_phase_stl()).
  std::string per_phase;
  /// Histograms of quality, angles, edge lengths... per iteration (paper Fig. 7):
  /// .svg, .csv or .json (check/history.hpp).
  std::string history;
  /// ASCII PLY and STL instead of binary.
  bool ascii = false;
};

/// One run: where the mesh comes from, how it is made and improved, where it goes.
struct MeshJob {
  /// To create a mesh: the input (anything load_input() reads), "" for the
  /// built-in demo scene. To improve `mesh`: the input it was made from, whose
  /// phase functions the pipeline needs ("" for none: passes such as flip).
  std::string input;
  /// How the input is read; its top_k is options.top_k.
  InputOptions input_options;
  /// A mesh file (PLY written by voronoimesh) to improve instead of creating
  /// one; "" creates one from `input`.
  std::string mesh;
  /// How the mesh is created and improved.
  MeshOptions options;
  /// The files the run writes.
  RunOutputs outputs;
};

/// Checks what a job can be checked for before any work, so that a typo fails
/// at once rather than after a long create: every option in range, the pipeline
/// against its registry, the output formats and that their folders can be
/// written.
/// @param job the job to check
/// @throws InvalidOption naming the option, for an option out of range (and for a pipeline that needs the
///         phase functions when job.mesh is improved without job.input)
/// @throws InvalidInput  for a bad pipeline or output format
/// @throws IoError       for an output that cannot be written
void check_job(const MeshJob& job);

/// Runs `job`: check_job(); read the input (or the mesh and the input it was
/// made from, refusing an input whose phases or domain cannot be the mesh's);
/// create the initial mesh unless job.mesh is given; improve it for
/// options.iterations; check it (options.validate); write the outputs.
/// @param job      what to mesh, how, and where to write it
/// @param observer watches the run; null for none. Not owned.
/// @return the mesh written
/// @throws Cancelled      when the observer asked to stop
/// @throws Error          everything else it throws is a vm::Error (core/errors.hpp): as check_job(),
///                        read_input(), create_mesh(), improve_mesh() and write_outputs() throw
/// @throws std::bad_alloc when memory runs out
NodeMesh run_job(const MeshJob& job, RunObserver* observer = nullptr);

/// The read stage: the scene of `path` (load_input() with `options`), or the
/// built-in demo scene when `path` is empty (refusing options for volumes, which
/// the demo would ignore).
/// @param path     the input, anything load_input() reads; "" for the built-in demo scene (demo_scene())
/// @param options  how the input is read
/// @param observer watches the stage; null for none. Not owned.
/// @return the scene
/// @throws InvalidInput as load_input(), and for options for volumes when `path` is empty
/// @throws IoError      as load_input()
Scene read_input(const std::string& path, const InputOptions& options = {}, RunObserver* observer = nullptr);

/// The grid create_mesh() samples: the scene's, or options.grid, with the cell
/// counts the lattice needs (grid_for_lattice()).
/// @param scene   the scene to mesh; its field must not be null
/// @param options the options of the run (grid, lattice)
/// @return the grid, on the scene's domain
/// @throws InvalidInput  for a null field
/// @throws InvalidOption for a grid or top_k out of range (and any other option: snap, iterations, threads)
GridSpec create_grid(const Scene& scene, const MeshOptions& options);

/// The lattice create takes: options.lattice when given, else cube6 for a
/// scene that needs every grid node (Scene::needs_every_grid_node, on its own
/// grid), else bcc.
/// @param options the options of the run (lattice, grid)
/// @param scene   the scene to mesh
/// @return the lattice
Lattice lattice_for(const MeshOptions& options, const Scene& scene);

/// The CreateParams of `options` for `scene`.
/// @param scene   the scene to mesh
/// @param options the options of the run
/// @return its lattice (lattice_for()), snap and close as CreateParams
CreateParams create_params(const Scene& scene, const MeshOptions& options);

/// Samples `scene.field` on create_grid() and creates the initial mesh (paper
/// sect. 4.1), with the phases' names and labels (NodeMesh::phase_names,
/// phase_labels) for writers, and with options.close the outside phase.
/// @param scene    the scene to mesh; its field must not be null
/// @param options  the options of the run
/// @param observer watches the sample and create stages; null for none. Not owned.
/// @return the initial mesh
/// @throws InvalidInput  for a null field; from sampling, for a NaN or infinite phase value
/// @throws InvalidOption for an option out of range or a grid too big for this machine's memory
/// @throws TopologyError if options.validate and the mesh fails validation (a bug, or unusable input)
/// @throws Cancelled     if the observer asked to stop
NodeMesh create_mesh(const Scene& scene, const MeshOptions& options = {}, RunObserver* observer = nullptr);

/// The pipeline a run of `options` improves with: options.pipeline, or if that
/// is empty and options.size is set, remesh:length=`size` before
/// kPassesAfterRemesh, else the default for the input: kLabelVolumePipeline when `scene` is
/// a label volume (Scene::voxel_grid), kScenePipeline for any other scene, and
/// kDefaultPipeline (the paper's) without a scene: a mesh read from a file is
/// not remeshed again.
/// @param options the options of the run
/// @param scene   the scene the mesh is created from; null for none
/// @return the pipeline, "name,name:key=value,..."
std::string pipeline_for(const MeshOptions& options, const Scene* scene);

/// The options a run creating its mesh from `scene` improves it with:
/// pipeline_for() `scene` as the pipeline, without the sizing options it has
/// taken in (they and a pipeline exclude each other), and stop_when_converged,
/// where unset, on for a label volume improved with its default pipeline.
/// @param options the options of the run
/// @param scene   the scene the mesh is created from
/// @return `options` so resolved: improve_mesh() takes them as they are
MeshOptions options_for_scene(MeshOptions options, const Scene& scene);

/// Runs options.pipeline (pipeline_for() without a scene) for
/// options.iterations on `mesh`, moving its nodes and flipping its edges in
/// place (paper Algorithm 1). Nodes no triangle uses are dropped first (the
/// others numbered in order), with a note to the observer.
/// @param mesh     the mesh to improve, changed in place
/// @param field    the phase functions `mesh` was created from (for a closed mesh without the outside
///                 phase, which is added: phases_of_mesh()); may be null when no pass needs it
/// @param options  the options of the run
/// @param observer watches the improve stage and every iteration; null for none. Not owned.
/// @return the iterations done (fewer than asked when stop_when_converged stops early)
/// @throws InvalidInput  for a bad pipeline or a pipeline that needs a field and has none
/// @throws InvalidOption for an option out of range
/// @throws TopologyError if `mesh` is not a valid interface mesh or (with options.validate) the result
///                       fails validation
/// @throws Cancelled     if the observer asked to stop
int improve_mesh(NodeMesh& mesh, std::shared_ptr<const PhaseField> field, const MeshOptions& options = {},
                 RunObserver* observer = nullptr);

/// Refuses an input that cannot be the one `mesh` was made from: phase ids its
/// phase functions do not have, phases named or labelled otherwise, or nodes
/// outside its domain.
/// @param mesh      the mesh
/// @param mesh_path its file, for the messages
/// @param scene     the input read
/// @param input     the input's file, for the messages
/// @throws InvalidInput naming `input` and what does not match
void check_field_matches(const NodeMesh& mesh, const std::string& mesh_path, const Scene& scene,
                         const std::string& input);

/// How far a mesh's nodes lie from the interface of the input it was made
/// from, and the grid spacing h to tell them in (`voronoimesh stats --field`).
struct MeshOffsets {
  InterfaceOffsets offsets;       ///< per class of nodes (interface_offsets())
  double spacing = 1;             ///< h: the mesh's grid_spacing, or when it does not say, the input's default grid's
  bool spacing_from_mesh = false; ///< whether h is the mesh's own
};

/// check_field_matches(), then interface_offsets() of `mesh` from `scene`'s phase functions.
/// @param mesh      the mesh
/// @param mesh_path its file, for the messages
/// @param scene     the input it was made from
/// @param input     the input's file, for the messages
/// @throws InvalidInput as check_field_matches()
MeshOffsets offsets_from_input(const NodeMesh& mesh, const std::string& mesh_path, const Scene& scene,
                               const std::string& input);

/// Where the voxel centres of the label volume `input` lie in `mesh`
/// (label_agreement()), the volume placed as load_input() placed it
/// (read_placed_volume()); none where `scene`, `input` as read with `options`,
/// is no label volume (Scene::phase_voxels empty) or the mesh is not closed.
/// `voronoimesh stats --field` and the Python module's stats() report it.
/// @param mesh    the mesh, with its phases' labels
/// @param scene   the input it was made from, as read (read_input())
/// @param input   the input's file
/// @param options how it was read
std::optional<LabelAgreement> label_agreement_from_input(const NodeMesh& mesh, const Scene& scene,
                                                         const std::string& input, const InputOptions& options);

/// Why label_agreement_from_input() locates no voxel centres of a label volume
/// in `mesh`: "" when it does, or when `scene` is no label volume (nothing to
/// locate, nothing to explain); else the reason, one line, for the report.
/// @param mesh  the mesh
/// @param scene the input it was made from, as read (read_input())
/// @return the reason, or ""
std::string voxel_centres_not_located(const NodeMesh& mesh, const Scene& scene);

/// create_mesh() then improve_mesh() with pipeline_for() the scene: the CLI's
/// `voronoimesh mesh` without the files. It never exits.
/// @param scene    the scene to mesh; its field must not be null
/// @param options  the options of the run
/// @param observer watches the run (progress, and whether to stop); null for none. Not owned.
/// @return the improved mesh
/// @throws Error everything it throws is a vm::Error (core/errors.hpp), as create_mesh() and
///               improve_mesh() throw (Cancelled when the observer asked to stop)
NodeMesh mesh_scene(const Scene& scene, const MeshOptions& options = {}, RunObserver* observer = nullptr);

/// The write stage: `mesh` to outputs.mesh and outputs.per_phase (the history,
/// which needs the iterations, run_job() writes).
/// @param mesh     the mesh to write
/// @param outputs  where to write it; an empty path writes nothing of that kind
/// @param observer watches the write stage; null for none. Not owned.
/// @throws InvalidInput as io::write_mesh(), for an unknown extension
/// @throws IoError      as io::write_mesh() and io::write_per_phase_stl(), if a file cannot be written
/// @throws Cancelled    if the observer asked to stop before anything was written
void write_outputs(const NodeMesh& mesh, const RunOutputs& outputs, RunObserver* observer = nullptr);

} // namespace vm
