// gpis_surface: a Gaussian-process implicit surface over every touch so far
// (touchcloud/gp/implicit_surface.hpp): a GP on the signed distance, zero on
// the touched points and +-offset_mm along the palm's normal outside and
// inside them. Each touch updates the model (a bordered Cholesky update
// between hyperparameter selections); its zero level set on a grid around
// the touched points is meshed by VTK's flying edges and sampled uniformly
// by area into the cloud this stage outputs (for the chamfer stage). The
// last mesh is written as PLY with each vertex's variance.
//
// form: exact fits every training point (a bordered Cholesky update per
// touch) and refuses a touch beyond exact_max_points; sparse summarises them
// by inducing points (touchcloud/gp/sparse_implicit_surface.hpp) for tens of
// thousands of points; exact_then_sparse is exact until a touch would pass
// exact_max_points, then the sparse form fitted to every touch so far (as if
// it had been sparse from the first), said in a note (fit.form).
//
// The palm's normal comes from the tactile cloud's sensor pose (against its
// z axis: the gel presses along +z of the sensor frame); without the tactile input each touch's normal
// is its patch's plane normal, turned away from the centroid of all points.
// With swept_mm the pose also gives the press's path: points back along it
// from the contact, outside at their distance from it (gp::add_swept_approach),
// so the GP does not close space a gel went through.
//
// table_z_mm: the object rests on a table there (base frame). The meshed
// field is the model's clipped to the space above the plane
// (gp::clip_above_table), so the mesh and the cloud out stop at the table and
// are closed by it where the model's inside reaches it: the face the object
// stands on, which no touch reaches. The `implicit` and `surface` outputs
// stay the model itself.
//
// surface: gp_mean meshes the GP's mean; local_quadrics meshes local
// quadrics of the touched points where they reach and the GP's mean elsewhere
// (quadric_mesh.hpp), for thin walls the GP's smooth field thickens (a mug's).
// Either way the `implicit` and `surface` outputs, which the planners read,
// are the GP.
//
// The `surface` output is the model as a press from above meets it
// (top_surface.hpp), for next_touch to choose where it is least certain; the
// `implicit` output is the model itself, for side_touch's touches from any
// side.
#include <memory>
#include <optional>
#include <sstream>
#include <variant>
#include <vector>

#include "quadric_mesh.hpp"
#include "top_surface.hpp"

#include "touchcloud/gp/held_implicit_model.hpp"
#include "touchcloud/gp/implicit_surface.hpp"
#include "touchcloud/gp/level_set_mesh.hpp"
#include "touchcloud/gp/sparse_implicit_surface.hpp"
#include "touchcloud/io/mesh_file.hpp"
#include "touchcloud/plugin.hpp"
#include "touchcloud/scoring/triangle_mesh.hpp"
#include "touchcloud/types/implicit_model.hpp"
#include "touchcloud/types/point_cloud.hpp"
#include "touchcloud/types/tactile_cloud.hpp"

namespace touchcloud {

enum class ImplicitForm { exact, sparse, exact_then_sparse };
enum class MeshedSurface { gp_mean, local_quadrics };

class GpisSurface final : public Stage {
  gp::ImplicitSurfaceOptions options_;
  ImplicitForm form_ = ImplicitForm::exact;
  std::int64_t exact_max_points_ = 10000;
  gp::SparseImplicitOptions sparse_;
  std::int64_t cells_ = 64;
  double margin_mm_ = 5.0;
  std::int64_t samples_ = 20000;
  std::optional<std::string> mesh_path_;
  std::optional<double> table_z_mm_;
  bool warned_below_table_ = false;
  std::int64_t threads_ = 0;
  double scale_floor_ = 1;  // the thin-plate R's floor last reported
  // Shared with the `surface` output until the next touch.
  std::variant<std::shared_ptr<gp::ImplicitSurface>, std::shared_ptr<gp::SparseImplicitSurface>> model_;
  std::vector<gp::ImplicitTouch> touches_;  // exact_then_sparse, while exact: for the sparse form's fit
  MeshedSurface meshed_ = MeshedSurface::gp_mean;
  gp::LocalQuadricOptions quadric_;
  // local_quadrics: the side's normal of each of the model's contact points, in their order.
  Eigen::MatrixX3d outward_;
  scoring::TriangleMesh mesh_;
  CloudConstPtr cloud_;
  double swept_mm_ = 0;
  double swept_step_mm_ = 4.0;
  double piece_support_mm_ = 0;
  bool plan_gaps_ = false;
  std::vector<Eigen::Vector3d> gaps_;  // plan_gaps: the last mesh's jump triangles' centroids
  CloudConstPtr candidates_;
  SurfaceModelPtr surface_;
  ImplicitModelPtr implicit_;

  void declare_parameters(ParameterSet& p) override {
    p.add("form", form_, ImplicitForm::exact,
          {{"exact", ImplicitForm::exact}, {"sparse", ImplicitForm::sparse},
           {"exact_then_sparse", ImplicitForm::exact_then_sparse}})
        .doc("exact: every training point in the GP (refused beyond exact_max_points); sparse: inducing points "
             "summarise them, for tens of thousands of points; exact_then_sparse: exact until a touch would pass "
             "exact_max_points, then sparse, fitted again to every touch (note fit.form)");
    p.add("exact_max_points", exact_max_points_, std::int64_t{10000}).at_least(1).unit("points")
        .doc("the exact form refuses a touch that would take it beyond this many training points (exact_then_sparse "
             "goes on in the sparse form there); "
             "its per-touch update passes 50 ms at about 2,700 points on one core and grows as the points squared "
             "(docs/benchmarks.md)");
    p.add("inducing_spacing_mm", sparse_.inducing_spacing_mm, 8.0).unit("mm").above(0.0)
        .doc("sparse form: least distance between two inducing sites (each a signed pair across the surface); "
             "smaller follows the exact form more closely at a cost that grows as the sites squared");
    p.add("kernel", options_.kernel, gp::ImplicitKernelKind::thin_plate,
          {{"thin_plate", gp::ImplicitKernelKind::thin_plate},
           {"matern32", gp::ImplicitKernelKind::matern32},
           {"matern52", gp::ImplicitKernelKind::matern52}})
        .doc("covariance of the signed distance: thin-plate (scale: at least the data's diameter) or Matern");
    p.add("offset_mm", options_.offset_mm, 2.0).unit("mm").above(0.0)
        .doc("distance of the signed points along the palm's normal, outside (+) and inside (-) the contact");
    p.add("swept_mm", swept_mm_, 0.0).unit("mm").at_least(0.0)
        .doc("how far back along each press's approach from its contact the GP is told the space is free (the gel "
             "went through it): points every swept_step_mm on the gel's axis, each outside at its distance from the "
             "contact; opens what the smooth field closes across a gap a press went through (a cup's mouth over its "
             "floor); needs input 'tactile' (the press's pose); 0: none");
    p.add("swept_step_mm", swept_step_mm_, 4.0).unit("mm").above(0.0)
        .doc("spacing of the swept points along the approach");
    p.add("offset_stride", options_.offset_stride, 4).at_least(1)
        .doc("every this-many-th contact point of a touch gets a signed pair");
    p.add("selection_points", options_.selection_points, Eigen::Index{400}).at_least(3).unit("points")
        .doc("hyperparameters are selected on an even stride of at most this many training points");
    p.add("reselect_growth", options_.reselect_growth, 0.5).at_least(0.0)
        .doc("select hyperparameters again once the training points have grown by this fraction (0: every touch)");
    p.add("max_noise_mm", options_.max_noise_mm, 0.5).unit("mm").above(0.0)
        .doc("largest noise standard deviation of the signed distance the selection may choose");
    p.add("min_noise_mm", options_.min_noise_mm, 0.01).unit("mm").above(0.0)
        .doc("smallest noise standard deviation (keeps repeated touches of one spot factorisable)");
    p.add("cells", cells_, std::int64_t{64}).at_least(2).unit("cells")
        .doc("grid cells along the longest side of the box around the touched points, for the level set");
    p.add("margin_mm", margin_mm_, 5.0).unit("mm").above(0.0)
        .doc("the grid's box reaches this far beyond the touched points");
    p.add("samples", samples_, std::int64_t{20000}).at_least(1).unit("points")
        .doc("points sampled uniformly by area on the mesh, the cloud out");
    p.add("threads", threads_, std::int64_t{0}).at_least(0).unit("threads")
        .doc("threads of the mean on the grid (0: one per core); the surface is the same for any count");
    p.add("table_z_mm", table_z_mm_).unit("mm")
        .doc("height of the table the object rests on, base frame (the simulator's table: 0): the mesh and the cloud "
             "out stop there and are closed by it where the surface's inside reaches it; not set: no table");
    p.add("surface", meshed_, MeshedSurface::gp_mean,
          {{"gp_mean", MeshedSurface::gp_mean}, {"local_quadrics", MeshedSurface::local_quadrics}})
        .doc("what is meshed: the GP's mean, or local quadrics of the touched points where they reach "
             "(quadric_reach_mm) and the GP's mean elsewhere, for thin walls the GP thickens; the planners read the "
             "GP either way");
    p.add("quadric_reach_mm", quadric_.reach_mm, 16.0).unit("mm").above(0.0)
        .doc("local_quadrics: how far across its normal a patch's quadric stands for the surface");
    p.add("free_support_mm", quadric_.free_support_mm, 0.0).unit("mm").at_least(0.0)
        .doc("local_quadrics: a triangle on a touched patch's quadric (within 1 mm, within this of its centre across "
             "its normal) is kept even where it lies in front of another patch: a gel pressed into a concave corner "
             "(a cup's wall meeting its floor) lay against both faces; 0: free space drops it");
    p.add("quadric_edge_deg", quadric_.edge_deg, 0.0).unit("deg").range(0.0, 179.0)
        .doc("local_quadrics: where the nearest patch and one turned more than this from it disagree in sign, the "
             "pair's solid decides (a convex edge: inside both; a concave one: inside either), so a face's plane is "
             "not carried past a sharp edge; 0: the nearest patch alone");
    p.add("free_radius_mm", quadric_.free_radius_mm, 7.0).unit("mm").above(0.0)
        .doc("local_quadrics: triangles in front of a touched patch, within this of its centre across its normal "
             "(where the gel lay), are dropped");
    p.add("plan_gaps", plan_gaps_, false)
        .doc("local_quadrics: the planner's candidates (the `candidates` output) take, besides the cloud, the centre "
             "of each triangle dropped where the field jumps: where the quadrics and the GP's mean disagree, a face "
             "no touch has found yet (a cup's inner wall behind its touched outer wall) which the mesh leaves out; "
             "false: the candidates are the cloud");
    p.add("piece_support_mm", piece_support_mm_, 0.0).unit("mm").at_least(0.0)
        .doc("a connected piece of the mesh none of whose vertices lies within this of a touched point is dropped "
             "(gp::drop_unsupported_pieces): the GP's mean alone put it there, far from every touch (counted in "
             "dropped_unsupported_triangles); 0: every piece is kept");
    p.add("mesh", mesh_path_).output_file()
        .doc("PLY file in the output folder for the last mesh, with each vertex's variance (mm^2); not set: none");
  }
  void on_check(RunContext&) override {
    if (!(options_.min_noise_mm <= options_.max_noise_mm))
      throw ParameterError("min_noise_mm", "must not exceed max_noise_mm");
    if (mesh_path_ && std::filesystem::path(*mesh_path_).extension() != ".ply")
      throw ParameterError("mesh", "'" + *mesh_path_ + "': a mesh is written as .ply");
    if (plan_gaps_ && meshed_ != MeshedSurface::local_quadrics)
      throw ParameterError("plan_gaps", "adds the local quadrics' mesh's gaps: set surface: local_quadrics");
  }
  void on_configure(RunContext&) override {
    options_.max_training_points = exact_max_points_;
    warned_below_table_ = false;
    touches_.clear();
    outward_.resize(0, 3);
    if (form_ != ImplicitForm::sparse)
      model_ = std::make_shared<gp::ImplicitSurface>(options_);
    else
      model_ = std::make_shared<gp::SparseImplicitSurface>(options_, sparse_);
  }

  void declare_ports(PortSet& ports) override {
    ports.input<CloudConstPtr>("cloud", "the points this touch adds, base frame, mm");
    ports.optional_input<TactileCloudPtr>("tactile", "the touch's tactile cloud: its sensor pose gives the palm's normal");
    ports.output<CloudConstPtr>("cloud", "points sampled on the zero level set, base frame, mm");
    ports.output<CloudConstPtr>("candidates", "points a planner may choose a touch among (side_touch's surface_points): "
                                              "the cloud, with plan_gaps the mesh's gaps too");
    ports.output<SurfaceModelPtr>("surface", "the implicit surface as a press from above meets it: its highest "
                                             "zero crossing over each (x, y) and the variance there, for next_touch");
    ports.output<ImplicitModelPtr>("implicit", "the implicit surface itself (signed distance and variance), for "
                                               "side_touch");
    ports.metric("training_points", "points", "contact and signed points the GP is fitted to");
    ports.metric("update_path", "", "how the model was updated: 1 bordered Cholesky update, 2 refactorised, "
                 "3 hyperparameters selected");
    ports.metric("lml", "", "log marginal likelihood on the selection's subset (at each selection)").higher_is_better();
    ports.metric("scale_mm", "mm", "kernel scale: the thin-plate's R or the Matern lengthscale");
    ports.metric("signal_variance_mm2", "mm^2", "kernel signal variance");
    ports.metric("noise_variance_mm2", "mm^2", "noise variance of the signed distance");
    ports.metric("jitter_mm2", "mm^2", "jitter added to the covariance's diagonal to factorise it");
    ports.metric("mesh_triangles", "", "triangles of the zero level set");
    ports.metric("dropped_unsupported_triangles", "",
                 "piece_support_mm: triangles of pieces of the mesh farther than that from every touched point");
    ports.metric("quadric_patches", "", "local_quadrics: patches fitted to the touched points");
    ports.metric("dropped_jump_triangles", "", "local_quadrics: triangles dropped where the field jumps");
    ports.metric("dropped_free_space_triangles", "", "local_quadrics: triangles dropped where a gel lay");
    ports.metric("max_vertex_variance_mm2", "mm^2", "largest variance at a vertex of the last mesh").final();
    ports.metric("mean_vertex_variance_mm2", "mm^2", "mean variance over the last mesh's vertices").final();
    ports.artifact(ArtifactRole::reconstructed_surface, "the last mesh (PLY) with per-vertex variance, with mesh set");
  }

  template <class Model>
  void update_and_mesh(std::shared_ptr<Model>& model, const gp::ImplicitTouch& touch, StageIO& io, RunContext& ctx) {
    // A model handed out does not change: the next touch goes to a copy
    // while another stage still holds it. The runner lets go of this stage's
    // last outputs before the call, so only a reader that keeps them does.
    surface_.reset();
    implicit_.reset();
    if (model.use_count() > 1) model = std::make_shared<Model>(*model);
    const gp::ImplicitUpdate update = model->add(touch);  // InputError names a touch it refuses
    static constexpr double kPath[] = {3, 1, 2};  // selected, bordered, refactorised
    ctx.metric("update_path", kPath[static_cast<int>(update.path)]);
    if (update.lml) ctx.metric("lml", *update.lml);
    ctx.metric("training_points", static_cast<double>(update.training_points), "points");
    ctx.metric("scale_mm", model->hyperparameters().lengthscale_mm, "mm");
    ctx.metric("signal_variance_mm2", model->hyperparameters().signal_variance_mm2, "mm^2");
    ctx.metric("noise_variance_mm2", model->hyperparameters().noise_variance_mm2, "mm^2");
    ctx.metric("jitter_mm2", update.jitter_mm2, "mm^2");
    if (update.scale_floor > scale_floor_) {
      scale_floor_ = update.scale_floor;
      std::ostringstream text;
      const int touch_number = run_touch(ctx, model->touches());
      text << "the thin-plate covariance was not positive definite with R near the touches' diameter (touches "
              "spread all round the object): R is kept at least " << scale_floor_ << " times their diameter from touch "
           << touch_number << " on";
      ctx.note("thin_plate_scale", text.str());
      ctx.log("warning: " + text.str());
    }

    const Eigen::MatrixX3d& contacts = model->contact_points();
    const gp::SampleGrid grid = table_z_mm_ ? gp::grid_around(contacts, margin_mm_, static_cast<int>(cells_), *table_z_mm_)
                                            : gp::grid_around(contacts, margin_mm_, static_cast<int>(cells_));
    if (table_z_mm_) warn_of_points_below_table(contacts, ctx);
    if (meshed_ == MeshedSurface::local_quadrics) {
      const gp::LocalQuadricSurface quadrics(contacts, outward_, quadric_);
      QuadricMeshCounts dropped;
      mesh_ = local_quadric_mesh(
          grid, quadrics, [&](const Eigen::MatrixX3d& q) { return model->mean(q, static_cast<int>(threads_)); },
          table_z_mm_, static_cast<int>(threads_), dropped, plan_gaps_);
      gaps_ = std::move(dropped.jump_centroids);
      ctx.metric("quadric_patches", static_cast<double>(quadrics.patches()));
      ctx.metric("dropped_jump_triangles", static_cast<double>(dropped.jumps));
      ctx.metric("dropped_free_space_triangles", static_cast<double>(dropped.free_space));
    } else {
      Eigen::VectorXd values = model->mean(grid.sample_points(), static_cast<int>(threads_));
      if (table_z_mm_) gp::clip_above_table(grid, *table_z_mm_, values);
      mesh_ = gp::zero_level_set(grid, values);
    }
    if (piece_support_mm_ > 0)
      ctx.metric("dropped_unsupported_triangles",
                 static_cast<double>(gp::drop_unsupported_pieces(mesh_, contacts, piece_support_mm_)));
    if (mesh_.triangles.empty()) throw RunError("the implicit surface's zero level set does not cross its grid");
    ctx.metric("mesh_triangles", static_cast<double>(mesh_.triangles.size()));
    if (io.wants("surface")) {
      // Down from the top of the meshed box, in 1 mm steps (then bisected).
      const double top_z_mm = model->contact_points().col(2).maxCoeff() + margin_mm_;
      surface_ = std::make_shared<ImplicitTopSurface<Model>>(model, top_z_mm, 1.0);
    }
    if (io.wants("implicit")) implicit_ = std::make_shared<gp::HeldImplicitModel<Model>>(model);
  }

  // Touched points well below the table are cut off the mesh: the table's
  // height or the touches are wrong. Said once.
  void warn_of_points_below_table(const Eigen::MatrixX3d& contacts, RunContext& ctx) {
    static constexpr double kBelowMm = 2.0;
    const double lowest = contacts.col(2).minCoeff();
    if (warned_below_table_ || lowest >= *table_z_mm_ - kBelowMm) return;
    warned_below_table_ = true;
    std::ostringstream text;
    text << "a touched point lies " << *table_z_mm_ - lowest << " mm below the table (table_z_mm " << *table_z_mm_
         << "): the mesh leaves out what lies below it; is table_z_mm the table's height in the base frame?";
    ctx.note("below_table", text.str());
    ctx.log("warning: " + text.str());
  }

  // The run's touch (the loop's iteration) where there is one, else the
  // model's: a touch that added no point reaches no model, so the model's
  // count lags the run's.
  static int run_touch(const RunContext& ctx, std::size_t model_touch) {
    return ctx.iteration() >= 0 ? ctx.iteration() + 1 : static_cast<int>(model_touch);
  }

  // exact_then_sparse: while exact, keeps the touch; when it would take the
  // exact form beyond exact_max_points, fits the sparse form to every touch
  // before it, in their order, and goes on with that.
  void switch_to_sparse_beyond_exact(const gp::ImplicitTouch& touch, RunContext& ctx) {
    const auto* exact = std::get_if<std::shared_ptr<gp::ImplicitSurface>>(&model_);
    if (!exact) return;
    const Eigen::Index before = (*exact)->training_size();
    if (before + gp::implicit_rows_of(touch, options_) <= exact_max_points_) {
      touches_.push_back(touch);
      return;
    }
    auto sparse = std::make_shared<gp::SparseImplicitSurface>(options_, sparse_);
    for (const gp::ImplicitTouch& t : touches_) sparse->add(t);
    touches_.clear();
    std::ostringstream text;
    const int touch_number = run_touch(ctx, sparse->touches() + 1);
    text << "exact form for touches 1-" << touch_number - 1 << " (" << before << " training points); touch "
         << touch_number << " would pass exact_max_points (" << exact_max_points_
         << "), so from it on the sparse form (inducing sites " << sparse_.inducing_spacing_mm
         << " mm apart), fitted again to every touch";
    ctx.note("form", text.str());
    ctx.log(text.str());
    model_ = std::move(sparse);
  }

  // The side each point of the touch came from: its palm's normal, or
  // without one what the GP takes (gp::checked_touch_normals), before the
  // model adds the touch's points to its contacts.
  void keep_for_quadrics(const gp::ImplicitTouch& touch, const RunContext& ctx) {
    const Eigen::Index from = outward_.rows(), k = touch.points_mm.rows();
    bool estimated = false;
    const Eigen::MatrixX3d side = std::visit(
        [&](const auto& model) {
          return gp::checked_touch_normals(
              touch, model->contact_points(),
              "implicit surface, touch " + std::to_string(run_touch(ctx, model->touches() + 1)), estimated);
        },
        model_);
    outward_.conservativeResize(from + k, 3);
    outward_.bottomRows(k) = side;
  }

  // The contact point nearest the sensor's axis: where the gel's apex met
  // the object, the end of the path its axis swept.
  static Eigen::Vector3d nearest_to_axis(const Eigen::MatrixX3d& points, const Eigen::Vector3d& origin,
                                         const Eigen::Vector3d& axis) {
    const Eigen::MatrixX3d v = points.rowwise() - origin.transpose();
    const Eigen::VectorXd along = v * axis;
    Eigen::Index best = 0;
    (v - along * axis.transpose()).rowwise().squaredNorm().minCoeff(&best);
    return points.row(best).transpose();
  }

  void on_process(StageIO& io, RunContext& ctx) override {
    const auto& cloud = io.input<CloudConstPtr>("cloud");
    if (!cloud) throw RunError("no cloud to add");
    if (cloud->empty()) {  // a touch that added nothing: the surface stays as it was
      if (!cloud_) throw RunError("no touched points yet: the implicit surface needs a touch with points");
      io.output("cloud", cloud_);
      io.output("candidates", candidates_);
      if (surface_) io.output<SurfaceModelPtr>("surface", surface_);
      if (implicit_) io.output<ImplicitModelPtr>("implicit", implicit_);
      return;
    }
    gp::ImplicitTouch touch;
    touch.points_mm.resize(static_cast<Eigen::Index>(cloud->size()), 3);
    for (std::size_t i = 0; i < cloud->size(); ++i)
      touch.points_mm.row(static_cast<Eigen::Index>(i)) << (*cloud)[i].x, (*cloud)[i].y, (*cloud)[i].z;
    if (const auto* tactile = io.optional_input<TactileCloudPtr>("tactile"); tactile && *tactile) {
      // The sensor's z points from the plate through the gel into the object.
      const Eigen::Isometry3d& pose = (*tactile)->pose.base_from_sensor;
      const Eigen::Vector3d palm_normal = -pose.linear().col(2).normalized();
      touch.normals = palm_normal.transpose().replicate(touch.points_mm.rows(), 1);
      if (swept_mm_ > 0)
        gp::add_swept_approach(touch, nearest_to_axis(touch.points_mm, pose.translation(), palm_normal), palm_normal,
                               swept_mm_, swept_step_mm_);
    } else if (swept_mm_ > 0) {
      throw InputError("swept_mm needs the press's approach: wire input 'tactile' (the touch's tactile cloud)");
    }
    if (meshed_ == MeshedSurface::local_quadrics) keep_for_quadrics(touch, ctx);
    if (form_ == ImplicitForm::exact_then_sparse) switch_to_sparse_beyond_exact(touch, ctx);
    std::visit([&](auto& model) { update_and_mesh(model, touch, io, ctx); }, model_);
    auto out = std::make_shared<PointCloud>();
    for (const Eigen::Vector3d& p : scoring::sample_surface(mesh_, static_cast<std::size_t>(samples_), ctx.rng()()))
      out->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
    cloud_ = out;
    io.output("cloud", cloud_);
    candidates_ = cloud_;
    if (plan_gaps_ && !gaps_.empty()) {
      auto with_gaps = std::make_shared<PointCloud>(*cloud_);
      for (const Eigen::Vector3d& p : gaps_)
        with_gaps->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
      candidates_ = with_gaps;
    }
    io.output("candidates", candidates_);
    if (surface_) io.output<SurfaceModelPtr>("surface", surface_);
    if (implicit_) io.output<ImplicitModelPtr>("implicit", implicit_);
  }

  void on_finish(RunContext& ctx) override {
    if (mesh_.triangles.empty()) return;
    Eigen::MatrixX3d vertices(static_cast<Eigen::Index>(mesh_.vertices.size()), 3);
    for (std::size_t i = 0; i < mesh_.vertices.size(); ++i) vertices.row(static_cast<Eigen::Index>(i)) = mesh_.vertices[i];
    const Eigen::VectorXd variance = std::visit([&](const auto& model) { return model->variance(vertices); }, model_);
    ctx.metric("max_vertex_variance_mm2", variance.maxCoeff(), "mm^2");
    ctx.metric("mean_vertex_variance_mm2", variance.mean(), "mm^2");
    if (!mesh_path_) return;
    write_mesh_ply(ctx.output_path(*mesh_path_), mesh_,
                   {{"variance", std::vector<double>(variance.data(), variance.data() + variance.size())}});
    ctx.artifact(ArtifactRole::reconstructed_surface, *mesh_path_,
                 {{"triangles", static_cast<std::int64_t>(mesh_.triangles.size())}});
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::GpisSurface, "gpis_surface", reconstruction,
                  "Fits a Gaussian-process implicit surface (signed distance) to touches from any side and meshes it")
