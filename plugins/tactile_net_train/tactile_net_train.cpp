// tactile_net_train: trains one of the ContactNet/TactileDepthNet report's networks (learning/
// tactile_nets.hpp) on a tactile dataset folder (touchcloud/io/
// tactile_dataset.hpp: its train/ split, with validation/ scored after every
// epoch), supervised: ContactNet on the contact masks (BCE), TactileDepthNet
// on the height maps (L2) with a trained ContactNet's probability as its
// fourth input channel. Adam, the report's augmentation; writes a checkpoint
// (weights, the optimiser's state, architecture, input size, toolkit
// version, the dataset's sensor) and the train and validation loss per epoch
// (CSV + PNG: the report's Figures 2-3). Resumable from a checkpoint of the
// same network; deterministic given --seed on one machine and thread count.
#include <chrono>
#include <climits>
#include <cmath>
#include <optional>

#include "touchcloud/file_write.hpp"
#include "touchcloud/io/tactile_dataset.hpp"
#include "touchcloud/io/tactile_sample_files.hpp"
#include "touchcloud/learning/checkpoint.hpp"
#include "touchcloud/learning/tactile_net_pair.hpp"
#include "touchcloud/learning/tactile_nets.hpp"
#include "touchcloud/learning/torch_io.hpp"
#include "touchcloud/learning/training_loop.hpp"
#include "touchcloud/number_text.hpp"
#include "touchcloud/plugin.hpp"

namespace touchcloud {

namespace lrn = touchcloud::learning;
namespace fs = std::filesystem;

namespace {
// One split of the dataset, as read at check.
struct Split {
  std::vector<cv::Mat> images, heights, masks;  // CV_8UC3, CV_32FC1 mm, CV_8UC1
};
}  // namespace

class TactileNetTrain final : public Stage {
  lrn::TactileNetShape shape_;
  std::string dataset_file_;
  std::optional<std::string> contact_checkpoint_, resume_from_;
  std::string checkpoint_, curve_csv_, curve_png_;
  int epochs_ = 10, batch_size_ = 8, threads_ = 1;
  lrn::LearningRateSchedule schedule_;
  std::optional<int> constant_epochs_;
  lrn::TactileAugmentation augmentation_;
  // Read at check.
  io::TactileDatasetInfo info_;
  cv::Mat reference_;
  Split train_, validation_;
  std::optional<lrn::Checkpoint> resume_;
  lrn::ContactNet contact_net_{nullptr};

  bool depth() const { return shape_.net == lrn::TactileNet::Depth; }

  void declare_parameters(ParameterSet& p) override {
    p.add("network", shape_.net, lrn::TactileNet::Contact,
          {{"contact_net", lrn::TactileNet::Contact}, {"tactile_depthnet", lrn::TactileNet::Depth}})
        .doc("which network: ContactNet (contact masks, BCE) or TactileDepthNet (height maps, L2)");
    p.add("dataset", dataset_file_, std::string()).input_file()
        .doc("the tactile dataset's dataset.yaml (train/ trains, validation/ scores; reference.png needed)");
    p.add("contact_checkpoint", contact_checkpoint_).input_file()
        .doc("tactile_depthnet only: the trained ContactNet whose probability is the depth network's fourth input");
    p.rule({"contact_checkpoint", "network"}, [this]() -> std::optional<std::string> {
      if (depth() && !contact_checkpoint_) return "network tactile_depthnet needs contact_checkpoint (a trained ContactNet)";
      if (!depth() && contact_checkpoint_) return "only network tactile_depthnet takes a contact_checkpoint";
      return std::nullopt;
    });
    p.add("width", shape_.width, 8).range(1, 256).unit("channels")
        .doc("base channel count (ContactNet: convolutions c, 2c, 2c, 4c, c, fc1 8c; TactileDepthNet: 2c)");
    p.add("epochs", epochs_, 10).range(1, 100000).unit("epochs").doc("epochs in all (the report: 10; a resumed run continues to this)");
    p.add("batch_size", batch_size_, 8).range(1, 4096).unit("samples").doc("samples per Adam step");
    p.add("learning_rate", schedule_.initial, 1e-3).above(0).doc("Adam's learning rate (the report: 0.001)");
    p.add("constant_epochs", constant_epochs_).at_least(0).unit("epochs")
        .doc("epochs before the rate is halved (not set: constant throughout, as the report)");
    p.add("halve_every", schedule_.halve_every, 10).at_least(1).unit("epochs")
        .doc("after constant_epochs, the rate is halved every this many epochs");
    p.add("max_rotation_deg", augmentation_.max_rotation_deg, 5.0).range(0, 180).unit("deg")
        .doc("augmentation: each training sample rotated by a uniform angle within +- this (the report: 5)");
    p.add("flip_probability", augmentation_.flip_probability, 0.5).range(0, 1)
        .doc("augmentation: probability of a left-right flip (the report: 0.5)");
    p.add("checkpoint", checkpoint_, std::string("tactile_net.ckpt")).output_file().doc("checkpoint file written");
    p.add("curve_csv", curve_csv_, std::string("tactile_net_curve.csv")).output_file()
        .doc("train and validation loss (and the validation metric) per epoch");
    p.add("curve_png", curve_png_, std::string("tactile_net_curve.png")).output_file()
        .doc("plot of the train and validation loss per epoch");
    p.add("resume_from", resume_from_).input_file()
        .doc("checkpoint to continue from (weights, optimiser state, epochs done); must be of the same network");
    // One thread: an epoch of the shipped ContactNet's training took 12.6 s on
    // one thread and 31.3 s on two on the shared 2-core machine (load 11).
    p.add("threads", threads_, 1).range(1, 256).doc("libtorch's intra-op threads (1: measured fastest on 2 cores shared with the other stages)");
  }

  void declare_ports(PortSet& ports) override {
    ports.metric("parameters", "", "trainable parameters of the network");
    ports.metric("gflops", "GFLOP", "floating-point operations of one forward pass on an image");
    ports.metric("training_s", "s", "time the training took");
    ports.metric("epochs_run", "epochs", "epochs this run trained (after a resumed checkpoint's)");
    ports.metric("final_loss", "", "training loss of the last epoch").lower_is_better();
    ports.metric("final_val_loss", "", "validation loss of the last epoch").lower_is_better();
    ports.metric("final_val_iou", "", "ContactNet: contact IoU on the validation split, last epoch").higher_is_better();
    ports.metric("final_val_rmse_contact_mm", "mm",
                 "TactileDepthNet: height RMSE over the true contact on the validation split, last epoch")
        .lower_is_better();
    ports.artifact(ArtifactRole::checkpoint, "the trained network: weights, architecture, input size, normalisation");
    ports.artifact(ArtifactRole::table, "the train/validation loss curve, one row per epoch (CSV)");
    ports.artifact(ArtifactRole::image, "the loss curve as a picture");
  }

  void on_check(RunContext&) override {
    const fs::path folder = fs::path(dataset_file_).parent_path();
    try {
      info_ = io::read_tactile_dataset_info(dataset_file_);
      shape_.input_width_px = info_.width_px;
      shape_.input_height_px = info_.height_px;
      if (const std::string problem = shape_.size_problem(); !problem.empty())
        throw InputError("dataset " + dataset_file_ + ": " + problem);
      const fs::path reference = folder / io::kTactileDatasetReference;
      if (!fs::exists(reference))
        throw InputError("dataset " + dataset_file_ + " has no " + io::kTactileDatasetReference +
                         " (the no-contact image): the networks take the difference to it");
      reference_ = io::read_dataset_image(reference, CV_8UC3, info_, dataset_file_);
      train_ = read_split(io::TactileSplit::Train);
      validation_ = read_split(io::TactileSplit::Validation);
    } catch (const InputError& e) {
      throw ParameterError("dataset", e.what());
    }
    if (contact_checkpoint_) {
      try {
        const lrn::CheckpointHeader h = lrn::read_checkpoint_header(*contact_checkpoint_);
        const auto contact = lrn::TactileNetShape::from_header(h, lrn::TactileNet::Contact, *contact_checkpoint_);
        if (contact.input_width_px != info_.width_px || contact.input_height_px != info_.height_px)
          throw InputError(*contact_checkpoint_ + ": the checkpoint is " + h.describe() + "; the dataset " +
                           dataset_file_ + " holds " + std::to_string(info_.width_px) + " x " +
                           std::to_string(info_.height_px) + " px images");
      } catch (const InputError& e) {
        throw ParameterError("contact_checkpoint", e.what());
      }
    }
    if (resume_from_) {
      try {
        resume_ = lrn::read_checkpoint(*resume_from_);
        lrn::require_same_network(resume_->header, shape_.header(), *resume_from_);
      } catch (const InputError& e) {
        throw ParameterError("resume_from", e.what());
      }
    }
  }

  Split read_split(io::TactileSplit split) const {
    Split out;
    for (const auto& s : io::list_tactile_dataset(fs::path(dataset_file_).parent_path(), split)) {
      out.images.push_back(io::read_dataset_image(s.image, CV_8UC3, info_, dataset_file_));
      io::SampleTruth truth = io::read_sample_truth(s, info_, dataset_file_);
      out.heights.push_back(truth.height_mm);
      out.masks.push_back(truth.contact_mask);
    }
    return out;
  }

  // The network's training loss of a batch, and what it predicted: contact
  // logits, or heights.
  torch::Tensor predict(torch::nn::Module& net, const torch::Tensor& difference) {
    if (!depth()) return static_cast<lrn::ContactNetImpl&>(net).forward(difference);
    torch::Tensor probability;
    {
      torch::NoGradGuard no_grad;
      probability = torch::sigmoid(contact_net_->forward(difference));
    }
    return static_cast<lrn::TactileDepthNetImpl&>(net).forward(difference, probability);
  }
  torch::Tensor loss(const torch::Tensor& prediction, const torch::Tensor& height, const torch::Tensor& mask) const {
    return depth() ? lrn::depth_loss(prediction, height) : lrn::contact_loss(prediction, mask);
  }
  static torch::Tensor mask_batch(const std::vector<cv::Mat>& masks, const std::vector<std::int64_t>& rows) {
    return lrn::image_batch(masks, rows).gt(0.5).to(torch::kFloat32);
  }

  void on_process(StageIO&, RunContext& ctx) override {
    torch::set_num_threads(threads_);
    ctx.used("threads", static_cast<std::int64_t>(torch::get_num_threads()));
    torch::manual_seed(ctx.rng()());
    schedule_.constant_epochs = constant_epochs_.value_or(INT_MAX);
    std::shared_ptr<torch::nn::Module> net;
    const torch::Tensor all_train = lrn::tactile_difference_batch(train_.images, reference_);
    const auto [mean, deviation] = lrn::channel_statistics(all_train);
    if (depth()) {
      lrn::TactileDepthNet d(shape_);
      d->set_normalisation(mean, deviation);
      net = d.ptr();
      const lrn::Checkpoint c = lrn::read_checkpoint(*contact_checkpoint_);
      contact_net_ = lrn::ContactNet(lrn::TactileNetShape::from_header(c.header, lrn::TactileNet::Contact, *contact_checkpoint_));
      lrn::load_module_bytes(*contact_net_, c.blob("weights", *contact_checkpoint_), *contact_checkpoint_);
      contact_net_->eval();
    } else {
      lrn::ContactNet c(shape_);
      c->set_normalisation(mean, deviation);
      double contact = 0, pixels = 0;
      for (const cv::Mat& m : train_.masks) contact += cv::countNonZero(m), pixels += static_cast<double>(m.total());
      c->set_contact_prior(contact / pixels);
      net = c.ptr();
    }
    torch::optim::Adam adam(net->parameters(), torch::optim::AdamOptions(schedule_.initial));
    int first_epoch = 0;
    if (resume_) {
      lrn::load_module_bytes(*net, resume_->blob("weights", *resume_from_), *resume_from_);
      lrn::load_optimizer_bytes(adam, resume_->blob("optimizer", *resume_from_), *resume_from_);
      if (const auto done = lrn::training_field(resume_->header, "epochs_done")) first_epoch = std::stoi(*done);
    }
    const auto parameters = lrn::tactile_net_parameters(shape_);
    const double flops = lrn::tactile_net_flops(shape_);
    ctx.log(shape_.header().describe() + ": " + std::to_string(parameters) + " parameters, " +
            number_text(std::round(flops / 1e6) / 1e3) + " GFLOPs per image; " + std::to_string(train_.images.size()) +
            " training and " + std::to_string(validation_.images.size()) + " validation samples, epochs " +
            std::to_string(first_epoch + 1) + ".." + std::to_string(epochs_));
    ctx.metric("parameters", static_cast<double>(parameters));
    ctx.metric("gflops", flops / 1e9, "GFLOP");

    const auto n = static_cast<std::int64_t>(train_.images.size());
    const std::string metric = depth() ? "val_rmse_contact_mm" : "val_iou";
    lrn::TrainingLoop loop;
    loop.schedule = schedule_;
    loop.first_epoch = first_epoch;
    loop.epochs = epochs_;
    loop.run_epoch = [&](int, double rate) {
      for (auto& group : adam.param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(rate);
      net->train();
      double sum = 0;
      for (const auto& rows : lrn::shuffled_batches(n, batch_size_, ctx.rng())) {
        torch::Tensor d = lrn::tactile_difference_batch(train_.images, reference_, rows);
        torch::Tensor h = lrn::image_batch(train_.heights, rows), m = mask_batch(train_.masks, rows);
        lrn::augment({&d, &h}, {&m}, augmentation_, ctx.rng());
        adam.zero_grad();
        const torch::Tensor l = loss(predict(*net, d), h, m);
        l.backward();
        adam.step();
        sum += l.item<double>() * static_cast<double>(rows.size());
      }
      std::vector<std::pair<std::string, double>> values{{"loss", sum / static_cast<double>(n)}};
      validate(*net, values, metric);
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
                                {"train_samples", std::to_string(n)},
                                {"validation_samples", std::to_string(validation_.images.size())},
                                {"batch_size", std::to_string(batch_size_)},
                                {"max_rotation_deg", number_text(augmentation_.max_rotation_deg)},
                                {"flip_probability", number_text(augmentation_.flip_probability)},
                                {"sensor", info_.sensor.empty() ? "unnamed" : info_.sensor},
                                {"mm_per_px", number_text(info_.mm_per_px)},
                                {"gel_thickness_mm", number_text(info_.gel_thickness_mm)}};
    if (contact_checkpoint_)
      c.header.training_fields.emplace_back("contact_checkpoint", fs::path(*contact_checkpoint_).filename().string());
    if (!records.empty())
      for (const auto& [name, v] : records.back().values) c.header.training_fields.emplace_back(name, number_text(v));
    c.blobs = {{"weights", lrn::module_bytes(*net)}, {"optimizer", lrn::optimizer_bytes(adam)}};
    write_file(ctx.output_path(checkpoint_), lrn::checkpoint_bytes(c));
    write_file(ctx.output_path(curve_csv_), lrn::curve_csv(records));
    write_file(ctx.output_path(curve_png_), lrn::curve_png(records, {"loss", "val_loss"}));
    ctx.artifact(ArtifactRole::checkpoint, checkpoint_, {{"epochs_done", std::int64_t{epochs_}}});
    ctx.artifact(ArtifactRole::table, curve_csv_);
    ctx.artifact(ArtifactRole::image, curve_png_, 
                 {{"caption", std::string("Training curve: training and validation loss per epoch")}});
    ctx.metric("training_s", seconds, "s");
    ctx.metric("epochs_run", static_cast<double>(records.size()), "epochs");
    if (!records.empty())
      for (const auto& [name, v] : records.back().values) ctx.metric("final_" + name, v);
  }

  // The validation split without augmentation: its loss, and the contact
  // IoU (probability > 0.5) or the height RMSE over the true contact (mm).
  void validate(torch::nn::Module& net, std::vector<std::pair<std::string, double>>& values, const std::string& metric) {
    torch::NoGradGuard no_grad;
    net.eval();
    const auto n = static_cast<std::int64_t>(validation_.images.size());
    double loss_sum = 0, a = 0, b = 0;  // IoU: intersection, union; RMSE: squared error, pixels
    for (std::int64_t start = 0; start < n; start += 16) {
      std::vector<std::int64_t> rows;
      for (std::int64_t i = start; i < std::min(n, start + 16); ++i) rows.push_back(i);
      const torch::Tensor d = lrn::tactile_difference_batch(validation_.images, reference_, rows);
      const torch::Tensor h = lrn::image_batch(validation_.heights, rows), m = mask_batch(validation_.masks, rows);
      const torch::Tensor prediction = predict(net, d);
      loss_sum += loss(prediction, h, m).item<double>() * static_cast<double>(rows.size());
      if (depth()) {
        a += ((prediction - h).pow(2) * m).sum().item<double>();
        b += m.sum().item<double>();
      } else {
        const torch::Tensor predicted = prediction.gt(0).to(torch::kFloat32);
        a += (predicted * m).sum().item<double>();
        b += (predicted + m).clamp_max(1).sum().item<double>();
      }
    }
    net.train();
    values.emplace_back("val_loss", loss_sum / static_cast<double>(n));
    if (b > 0) values.emplace_back(metric, depth() ? std::sqrt(a / b) : a / b);
  }
};

}  // namespace touchcloud

TOUCHCLOUD_PLUGIN(touchcloud::TactileNetTrain, "tactile_net_train", learning,
                  "Trains ContactNet or TactileDepthNet on a tactile dataset folder; writes a checkpoint "
                  "and the train/validation loss curve")
