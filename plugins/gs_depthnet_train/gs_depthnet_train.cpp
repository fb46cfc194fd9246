// gs_depthnet_train: trains GS-DepthNet (the GS-DepthNet paper, Section III-IV) on a
// dense stereo dataset folder, self-supervised (the images and the contact
// masks; ground truth disparities, where the folder has them, only give
// validation metrics per epoch), and writes a checkpoint (weights, the
// optimiser's state, architecture, input size, toolkit version) and the
// training curve (CSV + PNG). Resumable from a checkpoint of the same
// network; deterministic given --seed on one machine and thread count.
#include <chrono>
#include <cmath>
#include <optional>

#include "touchcloud/file_write.hpp"
#include "touchcloud/imaging/contact_region.hpp"
#include "touchcloud/imaging/disparity_matcher.hpp"
#include "touchcloud/learning/checkpoint.hpp"
#include "touchcloud/learning/gs_depthnet.hpp"
#include "touchcloud/learning/host_memory.hpp"
#include "touchcloud/learning/image_losses.hpp"
#include "touchcloud/learning/reference_disparity.hpp"
#include "touchcloud/learning/stereo_samples.hpp"
#include "touchcloud/learning/torch_io.hpp"
#include "touchcloud/learning/training_loop.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/plugin.hpp"

namespace touchcloud {

namespace lrn = touchcloud::learning;

class GsDepthNetTrain final : public Stage {
  std::string index_;
  std::optional<std::string> extra_index_, resume_from_, rest_index_;
  std::string checkpoint_, curve_csv_, curve_png_;
  int epochs_ = 40, batch_size_ = 8, threads_ = 2;
  std::optional<int> crop_rows_;
  lrn::LearningRateSchedule schedule_;
  std::array<double, 2> betas_{0.9, 0.999};
  double epsilon_ = 1e-8;
  lrn::LossWeights weights_;
  lrn::GsDepthNetShape shape_;
  enum class ContactMasks { RestPair, Dataset };
  ContactMasks contact_masks_ = ContactMasks::RestPair;
  bool save_optimizer_ = true;
  imaging::ContactRegionOptions contact_;
  imaging::MatcherOptions reference_matcher_;
  // Read at check.
  std::vector<lrn::StereoSample> samples_;
  std::optional<lrn::StereoSample> rest_pair_;
  std::optional<lrn::Checkpoint> resume_;

  void declare_parameters(ParameterSet& p) override {
    p.add("index", index_, std::string()).input_file()
        .doc("the training dataset's index.csv (touchcloud/io/stereo_dataset.hpp), pairs at the network's input size");
    p.add("extra_index", extra_index_).input_file()
        .doc("a second dataset's index.csv trained on with the first (same image size)");
    p.add("epochs", epochs_, 40).range(1, 100000).unit("epochs").doc("epochs in all (a resumed run continues to this)");
    p.add("batch_size", batch_size_, 8).range(1, 4096).unit("pairs").doc("pairs per Adam step (the paper: 32)");
    p.add("learning_rate", schedule_.initial, 1e-4).above(0).doc("Adam's initial learning rate (the paper: 1e-4)");
    p.add("constant_epochs", schedule_.constant_epochs, 30).at_least(0).unit("epochs")
        .doc("epochs at the initial learning rate before it is halved (the paper: 30)");
    p.add("halve_every", schedule_.halve_every, 10).at_least(1).unit("epochs")
        .doc("then the rate is halved every this many epochs (the paper: 10)");
    // The paper prints beta2 = 0.900; with beta1 = 0.9 that reads as a typo
    // for Adam's usual 0.999, which is the default here.
    p.add("betas", betas_, std::array<double, 2>{0.9, 0.999}).range(0, 0.999999)
        .doc("Adam's beta1 and beta2 (the paper's 'beta2 = 0.900' taken as a typo for 0.999)");
    p.add("epsilon", epsilon_, 1e-8).above(0).doc("Adam's epsilon");
    p.add("w_ap", weights_.w_ap, 1.0).at_least(0).doc("appearance loss weight (Eq. 2)");
    p.add("alpha", weights_.alpha, 0.85).range(0, 1).doc("SSIM share of the appearance loss (Eq. 2)");
    p.add("w_ds", weights_.w_ds, 0.01).at_least(0).doc("smoothness weight (Eq. 3), divided by each scale's down-scaling factor r");
    p.add("w_lr", weights_.w_lr, 1.0).at_least(0).doc("weighted left-right consistency weight (Eq. 4-5)");
    p.add("w_se", weights_.w_se, 1e-4).at_least(0).doc("contact semantic loss weight (Eq. 6)");
    p.add("appearance_loss", weights_.appearance, true).doc("use the appearance term");
    p.add("appearance_resolution", weights_.appearance_resolution, lrn::AppearanceResolution::Input,
          {{"input", lrn::AppearanceResolution::Input}, {"scale", lrn::AppearanceResolution::Scale}})
        .doc("compare each scale's reconstruction at the input resolution (the paper) or at the scale's own, "
             "images downsampled (Monodepth's; finds disparities many pixels off)");
    p.add("smoothness_loss", weights_.smoothness, true).doc("use the smoothness term");
    p.add("lr_loss", weights_.lr_consistency, true).doc("use the left-right consistency term (false: Table I's 'Ours no LR')");
    p.add("se_loss", weights_.semantic, true).doc("use the contact semantic term (false: Table I's 'Ours no SE')");
    p.add("width", shape_.width, 8).range(1, 256).unit("channels").doc("channels of the first encoder block (the network's width)");
    p.add("d_max_px", shape_.d_max_px, 12.0).above(0).unit("px")
        .doc("output range above min_disparity_px, relative to the gel at rest: offset + d_max * sigmoid (the "
             "paper: 12 px at 256 x 256)");
    p.add("min_disparity_px", shape_.min_disparity_px, -1.0).unit("px")
        .doc("smallest disparity the network outputs, relative to the gel at rest (the paper: 0; below 0 leaves "
             "room for the rest disparity's fitting error)");
    p.add("rest_index", rest_index_).input_file()
        .doc("index.csv whose first pair shows the gel at rest (no contact), as the training pairs are "
             "rectified: SGBM's disparities of it are the network's zero (needed unless resume_from is set)");
    p.add("reference_min_disparity_px", reference_matcher_.min_disparity_px, 0).unit("px")
        .doc("smallest disparity SGBM searches in the rest pair");
    p.add("reference_num_disparities", reference_matcher_.num_disparities, 128).range(16, 1024).unit("px")
        .doc("disparities SGBM searches for the rest disparity, from reference_min_disparity_px (a multiple of 16)");
    p.add("contact_masks", contact_masks_, ContactMasks::RestPair,
          {{"rest_pair", ContactMasks::RestPair}, {"dataset", ContactMasks::Dataset}})
        .doc("the semantic loss's contact masks: contact_mask's algorithm on each pair against the rest pair "
             "(rest_pair: no labels, as the paper's masks come from a network, not from ground truth), or each "
             "row's contact_mask file (dataset: masks labelled by hand; a row without one is refused)");
    p.add("contact_threshold_grey", contact_.threshold_grey, 12.0).above(0).below(255).unit("grey levels")
        .doc("contact_mask's threshold_grey for the masks computed against the rest pair (12: the best agreement "
             "with the simulator's true masks on gs_depthnet_dataset.yaml's noisy presses, mean IoU 0.65)");
    p.add("checkpoint", checkpoint_, std::string("gs_depthnet.ckpt")).output_file().doc("checkpoint file written");
    p.add("curve_csv", curve_csv_, std::string("training_curve.csv")).output_file().doc("loss terms and metrics per epoch");
    p.add("curve_png", curve_png_, std::string("training_curve.png")).output_file().doc("plot of the training curve");
    p.add("save_optimizer", save_optimizer_, true)
        .doc("write Adam's state into the checkpoint (needed to resume from it; false: weights only, about a "
             "third of the file, for a shipped model)");
    p.add("resume_from", resume_from_).input_file()
        .doc("checkpoint to continue from (weights, optimiser state, epochs done); must be of the same network");
    p.add("threads", threads_, 2).range(1, 256).doc("libtorch's intra-op threads");
    p.add("crop_rows", crop_rows_).range(32, 4096).unit("px")
        .doc("train each batch on a band of this many rows at a random offset (a multiple of 32; the network is "
             "convolutional and sees whole images in validation and inference): a step costs about crop_rows / "
             "height of one on whole pairs. Not set: whole pairs");
    p.rule({"crop_rows"}, [this]() -> std::optional<std::string> {
      if (crop_rows_ && *crop_rows_ % 32) return "is " + std::to_string(*crop_rows_) + ", not a multiple of 32";
      return std::nullopt;
    });
  }

  void declare_ports(PortSet& ports) override {
    ports.metric("parameters", "", "trainable parameters of the network");
    ports.metric("gflops", "GFLOP", "floating-point operations of one forward pass on a pair");
    ports.metric("training_s", "s", "time the training took");
    ports.metric("epochs_run", "epochs", "epochs this run trained (after a resumed checkpoint's)");
    ports.metric("final_loss", "", "total loss of the last epoch").lower_is_better();
    ports.metric("final_appearance", "", "appearance (photometric) loss term of the last epoch").lower_is_better();
    ports.metric("final_smoothness", "", "smoothness loss term of the last epoch").lower_is_better();
    ports.metric("final_lr_consistency", "", "left-right consistency loss term of the last epoch").lower_is_better();
    ports.metric("final_semantic", "", "semantic (contact) loss term of the last epoch").lower_is_better();
    ports.metric("final_val_epe_px", "px", "mean end-point error on the pairs with true disparity, last epoch")
        .lower_is_better();
    ports.metric("final_val_epe_contact_px", "px", "the same over their contact region").lower_is_better();
    ports.artifact(ArtifactRole::checkpoint, "the trained network: weights, architecture, input size, rest disparity");
    ports.artifact(ArtifactRole::table, "the training curve, one row per epoch (CSV)");
    ports.artifact(ArtifactRole::image, "the training curve as a picture");
  }

  void on_check(RunContext& ctx) override {
    for (const auto& [param, file] : {std::pair<std::string, std::optional<std::string>>{"index", index_},
                                      {"extra_index", extra_index_}}) {
      if (!file) continue;
      lrn::StereoSamples set;
      try {
        set = lrn::read_stereo_samples(*file);
      } catch (const InputError& e) {
        throw ParameterError(param, e.what());
      }
      if (set.camera.width_px != shape_.input_width_px || set.camera.height_px != shape_.input_height_px) {
        if (param == "index") {
          shape_.input_width_px = set.camera.width_px;
          shape_.input_height_px = set.camera.height_px;
        } else {
          throw ParameterError(param, *file + ": pairs of " + std::to_string(set.camera.width_px) + " x " +
                                          std::to_string(set.camera.height_px) + " px; the first dataset's are " +
                                          std::to_string(shape_.input_width_px) + " x " +
                                          std::to_string(shape_.input_height_px));
        }
      }
      if (shape_.input_width_px % 32 || shape_.input_height_px % 32)
        throw ParameterError(param, *file + ": pairs of " + std::to_string(shape_.input_width_px) + " x " +
                                        std::to_string(shape_.input_height_px) +
                                        " px; GS-DepthNet needs both sides multiples of 32");
      for (auto& s : set.samples) samples_.push_back(std::move(s));
    }
    if (resume_from_) {
      try {
        resume_ = lrn::read_checkpoint(*resume_from_);
        lrn::require_same_network(resume_->header, shape_.header(), *resume_from_);
      } catch (const InputError& e) {
        throw ParameterError("resume_from", e.what());
      }
    }
    reference_matcher_.method = imaging::MatchMethod::SemiGlobal;
    reference_matcher_.full_width = true;  // the gel reaches the image's first columns
    reference_matcher_.validate();
    if (!resume_ && !rest_index_)
      throw ParameterError("rest_index", "is not set: the network's zero is the gel at rest, measured from a pair "
                                         "of it (or continue a checkpoint: resume_from)");
    if (crop_rows_ && *crop_rows_ > shape_.input_height_px)
      throw ParameterError("crop_rows", std::to_string(*crop_rows_) + " rows; the pairs have " +
                                            std::to_string(shape_.input_height_px));
    if (rest_index_) rest_pair_ = read_rest_pair();
    add_contact_masks(ctx);
  }

  // rest_index's first pair, at the training pairs' size.
  lrn::StereoSample read_rest_pair() const {
    lrn::StereoSamples rest;
    try {
      rest = lrn::read_stereo_samples(*rest_index_);
    } catch (const InputError& e) {
      throw ParameterError("rest_index", e.what());
    }
    lrn::StereoSample pair = std::move(rest.samples.front());
    if (pair.left.cols != shape_.input_width_px || pair.left.rows != shape_.input_height_px)
      throw ParameterError("rest_index", pair.where + ": a pair of " + std::to_string(pair.left.cols) + " x " +
                                             std::to_string(pair.left.rows) + " px; the training pairs are " +
                                             std::to_string(shape_.input_width_px) + " x " +
                                             std::to_string(shape_.input_height_px));
    return pair;
  }

  // The gel at rest: SGBM's left and right disparities of the rest pair
  // (rest_index's first row), filtered and filled. No ground truth.
  lrn::ReferenceDisparity measure_reference(RunContext& ctx) const {
    const lrn::StereoSample& pair = *rest_pair_;
    const auto d = imaging::DisparityMatcher(reference_matcher_).match(pair.left, pair.right, pair.where);
    auto r = lrn::reference_from_rest(d.left_px, d.valid_left, d.right_px, d.valid_right, pair.where);
    double lo = 0, hi = 0;
    cv::minMaxLoc(r.left_px, &lo, &hi, nullptr, nullptr, r.gel_left);
    ctx.log("rest disparity (SGBM of " + pair.where + "): " + number_text(std::round(lo * 10) / 10) + " to " +
            number_text(std::round(hi * 10) / 10) + " px over the left view's gel, " +
            std::to_string(cv::countNonZero(r.gel_left)) + " px");
    return r;
  }

  // Every sample's contact mask for the semantic loss: contact_mask's
  // algorithm against the rest pair's left view, or the row's own file.
  void add_contact_masks(RunContext& ctx) {
    if (!weights_.semantic) return;
    double lo = 100, hi = 0, iou_sum = 0;
    int labelled = 0;
    for (auto& s : samples_) {
      if (contact_masks_ == ContactMasks::Dataset) {
        if (s.contact_mask.empty())
          throw ParameterError("contact_masks", s.where + ": no contact_mask file (contact_masks: dataset takes "
                                                          "each row's; rest_pair computes them)");
        continue;
      }
      if (!rest_pair_)
        throw ParameterError("contact_masks", "rest_pair needs rest_index (a resumed training reads no rest pair): "
                                              "set rest_index, or contact_masks: dataset");
      const cv::Mat mask = imaging::contact_region(s.left, rest_pair_->left, contact_);
      const double share = 100.0 * cv::countNonZero(mask) / static_cast<double>(mask.total());
      lo = std::min(lo, share), hi = std::max(hi, share);
      if (!s.contact_mask.empty()) {  // a row's own mask (a label, or the simulator's truth): how they agree
        const double both = cv::countNonZero(mask & s.contact_mask), either = cv::countNonZero(mask | s.contact_mask);
        iou_sum += either > 0 ? both / either : 1.0;
        ++labelled;
      }
      s.contact_mask = mask;
    }
    if (contact_masks_ != ContactMasks::RestPair || samples_.empty()) return;
    std::string line = "contact masks against the rest pair: " + std::to_string(samples_.size()) + " pairs, " +
                       number_text(std::round(lo)) + " to " + number_text(std::round(hi)) + " % of the pixels";
    if (labelled > 0)
      line += "; IoU with the rows' own contact_mask files " + number_text(std::round(iou_sum / labelled * 100) / 100) +
              " (mean of " + std::to_string(labelled) + ")";
    ctx.log(line);
  }

  void on_process(StageIO&, RunContext& ctx) override {
    torch::set_num_threads(threads_);
    lrn::keep_freed_memory_for_reuse();  // a pass's activations are not faulted in again
    ctx.used("threads", static_cast<std::int64_t>(torch::get_num_threads()));
    torch::manual_seed(ctx.rng()());
    const lrn::ReferenceDisparity reference =
        resume_ ? lrn::ReferenceDisparity::parse(resume_->blob("rest_disparity", *resume_from_), *resume_from_)
                : measure_reference(ctx);
    lrn::GsDepthNet net(shape_, reference);
    torch::optim::Adam adam(net->parameters(), torch::optim::AdamOptions(schedule_.initial)
                                                   .betas({betas_[0], betas_[1]})
                                                   .eps(epsilon_));
    int first_epoch = 0;
    if (resume_) {
      lrn::load_module_bytes(*net, resume_->blob("weights", *resume_from_), *resume_from_);
      lrn::load_optimizer_bytes(adam, resume_->blob("optimizer", *resume_from_), *resume_from_);
      for (const auto& [name, value] : resume_->header.training_fields)
        if (name == "epochs_done") first_epoch = std::stoi(value);
    }
    const auto params = lrn::gs_depthnet_parameters(shape_);
    const double flops = lrn::gs_depthnet_flops(shape_);
    ctx.log("GS-DepthNet width " + std::to_string(shape_.width) + ": " + std::to_string(params) + " parameters, " +
            number_text(std::round(flops / 1e7) / 100) + " GFLOPs per " + std::to_string(shape_.input_width_px) +
            " x " + std::to_string(shape_.input_height_px) + " pair; " + std::to_string(samples_.size()) +
            " pairs, epochs " + std::to_string(first_epoch + 1) + ".." + std::to_string(epochs_));
    ctx.metric("parameters", static_cast<double>(params));
    ctx.metric("gflops", flops / 1e9, "GFLOP");

    std::vector<cv::Mat> lefts, rights, masks;
    for (const auto& s : samples_) {
      lefts.push_back(s.left);
      rights.push_back(s.right);
      masks.push_back(s.contact_mask.empty() ? cv::Mat(s.left.size(), CV_8UC1, cv::Scalar(0)) : s.contact_mask);
    }
    const torch::Tensor left_all = lrn::image_batch(lefts), right_all = lrn::image_batch(rights);
    const torch::Tensor contact_all = lrn::image_batch(masks).gt(0.5).to(torch::kFloat32);
    const auto n = static_cast<std::int64_t>(samples_.size());

    lrn::TrainingLoop loop;
    loop.schedule = schedule_;
    loop.first_epoch = first_epoch;
    loop.epochs = epochs_;
    loop.run_epoch = [&](int, double rate) {
      for (auto& group : adam.param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(rate);
      net->train();
      double sums[5] = {0, 0, 0, 0, 0};
      for (const auto& batch : lrn::shuffled_batches(n, batch_size_, ctx.rng())) {
        const torch::Tensor rows = torch::tensor(batch, torch::kLong);
        torch::Tensor l = left_all.index_select(0, rows), r = right_all.index_select(0, rows);
        torch::Tensor m = contact_all.index_select(0, rows);
        std::int64_t row0 = 0, height = shape_.input_height_px;
        if (crop_rows_) {
          height = *crop_rows_;
          const int bands = (shape_.input_height_px - *crop_rows_) / 32;
          row0 = 32 * std::uniform_int_distribution<int>(0, bands)(ctx.rng());
          l = l.narrow(2, row0, height);
          r = r.narrow(2, row0, height);
          m = m.narrow(2, row0, height);
        }
        adam.zero_grad();
        const auto terms = lrn::gs_depthnet_loss(net->forward(l, r, row0), l, r, m, weights_,
                                                 net->gel_mask(false, row0, height), net->gel_mask(true, row0, height));
        terms.total.backward();
        adam.step();
        const double share = static_cast<double>(batch.size()) / static_cast<double>(n);
        const torch::Tensor* parts[5] = {&terms.total, &terms.appearance, &terms.smoothness, &terms.lr_consistency,
                                         &terms.semantic};
        for (int k = 0; k < 5; ++k) sums[k] += parts[k]->item<double>() * share;
      }
      std::vector<std::pair<std::string, double>> values = {
          {"loss", sums[0]}, {"appearance", sums[1]}, {"smoothness", sums[2]}, {"lr_consistency", sums[3]},
          {"semantic", sums[4]}};
      validate(net, left_all, right_all, contact_all, values);
      return values;
    };
    loop.after_epoch = [&](const lrn::EpochRecord& r) {
      ctx.log(lrn::epoch_line(r, epochs_));
      ctx.progress(r.epoch + 1, epochs_, "epochs");
    };
    ctx.progress(std::min(first_epoch, epochs_), epochs_, "epochs");  // a resumed run may be done already
    const auto start = std::chrono::steady_clock::now();
    const auto records = loop.run();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    lrn::Checkpoint c;
    c.header = shape_.header();
    c.header.training_fields = {{"epochs_done", std::to_string(epochs_)},
                                {"seed", std::to_string(ctx.seed())},
                                {"pairs", std::to_string(n)},
                                {"batch_size", std::to_string(batch_size_)},
                                {"lr_loss", weights_.lr_consistency ? "on" : "off"},
                                {"se_loss", weights_.semantic ? "on" : "off"},
                                {"appearance_resolution",
                                 weights_.appearance_resolution == lrn::AppearanceResolution::Input ? "input" : "scale"}};
    if (!records.empty())
      for (const auto& [name, v] : records.back().values) c.header.training_fields.emplace_back(name, number_text(v));
    c.blobs = {{"weights", lrn::module_bytes(*net)}, {"rest_disparity", reference.bytes()}};
    if (save_optimizer_) c.blobs.emplace_back("optimizer", lrn::optimizer_bytes(adam));
    write_file(ctx.output_path(checkpoint_), lrn::checkpoint_bytes(c));
    write_file(ctx.output_path(curve_csv_), lrn::curve_csv(records));
    write_file(ctx.output_path(curve_png_),
               lrn::curve_png(records, {"loss", "appearance", "smoothness", "lr_consistency", "semantic", "val_epe_px"}));
    ctx.artifact(ArtifactRole::checkpoint, checkpoint_, {{"epochs_done", std::int64_t{epochs_}}});
    ctx.artifact(ArtifactRole::table, curve_csv_);
    ctx.artifact(ArtifactRole::image, curve_png_, 
                 {{"caption", std::string("GS-DepthNet's training curve: the loss and its terms per epoch, and the "
                                          "validation end-point error (px) where the pairs have true disparity")}});
    ctx.metric("training_s", seconds, "s");
    ctx.metric("epochs_run", static_cast<double>(records.size()), "epochs");
    if (!records.empty())
      for (const auto& [name, v] : records.back().values) ctx.metric("final_" + name, v);
  }

  // Validation against the ground truth disparities, where the samples have
  // them: the mean end-point error of Eq. 7's average over valid pixels,
  // and over the contact region.
  void validate(lrn::GsDepthNet& net, const torch::Tensor& left_all, const torch::Tensor& right_all,
                const torch::Tensor& contact_all, std::vector<std::pair<std::string, double>>& values) {
    std::vector<std::int64_t> rows;
    std::vector<cv::Mat> truth, valid;
    for (std::size_t i = 0; i < samples_.size(); ++i)
      if (!samples_[i].disparity_left_px.empty()) {
        rows.push_back(static_cast<std::int64_t>(i));
        truth.push_back(samples_[i].disparity_left_px);
        valid.push_back(samples_[i].valid_left);
      }
    if (rows.empty()) return;
    torch::NoGradGuard no_grad;
    net->eval();
    const torch::Tensor t = lrn::image_batch(truth), v = lrn::image_batch(valid).gt(0.5).to(torch::kFloat32);
    double error = 0, count = 0, error_contact = 0, count_contact = 0;
    for (std::size_t start = 0; start < rows.size(); start += 16) {
      const std::size_t end = std::min(rows.size(), start + 16);
      const torch::Tensor pick = torch::tensor(std::vector<std::int64_t>(rows.begin() + start, rows.begin() + end), torch::kLong);
      const auto scales = net->forward(left_all.index_select(0, pick), right_all.index_select(0, pick));
      const torch::Tensor dl = scales.back().left, dr = scales.back().right;
      const torch::Tensor mean = (dl + lrn::sample_along_x(dr, -dl)) / 2;
      const torch::Tensor local = torch::arange(static_cast<std::int64_t>(start), static_cast<std::int64_t>(end), torch::kLong);
      const torch::Tensor vv = v.index_select(0, local), tt = t.index_select(0, local);
      const torch::Tensor abs = (mean - tt).abs() * vv;
      const torch::Tensor c = contact_all.index_select(0, pick) * vv;
      error += abs.sum().item<double>();
      count += vv.sum().item<double>();
      error_contact += (abs * c).sum().item<double>();
      count_contact += c.sum().item<double>();
    }
    net->train();
    if (count > 0) values.emplace_back("val_epe_px", error / count);
    if (count_contact > 0) values.emplace_back("val_epe_contact_px", error_contact / count_contact);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::GsDepthNetTrain, "gs_depthnet_train", learning,
                  "Trains GS-DepthNet (self-supervised stereo disparity) on a dataset folder; writes a checkpoint "
                  "and the training curve")
