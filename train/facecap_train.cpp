// facecap-train: builds the expression-mapping training set and trains the
// CycleGAN mappings (LibTorch). Not needed at run time: facecap reads the
// exported networks with Eigen.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cyclegan.hpp"
#include "facecap/core/atomic_file.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/paths.hpp"
#include "facecap/expr/training_data.hpp"
#include "facecap/model/model_cache.hpp"

namespace fs = std::filesystem;
using namespace facecap;

namespace {

Eigen::VectorXf mean(const std::vector<Eigen::VectorXf>& v) {
  Eigen::VectorXf m = Eigen::VectorXf::Zero(v.front().size());
  for (const auto& x : v) m += x / float(v.size());
  return m;
}

void train_pair(const std::vector<LabeledWeights>& data, Emotion emotion, const fs::path& out,
                const CycleGanOptions& options, const std::string& source) {
  std::vector<Eigen::VectorXf> x, y;
  for (const LabeledWeights& r : data) {
    if (r.label == Emotion::kNeutral) x.push_back(r.weights);
    if (r.label == emotion) y.push_back(r.weights);
  }
  if (x.empty() || y.empty()) {
    throw Error("training data has no " + std::string(x.empty() ? "neutral" : to_string(emotion)) + " rows");
  }
  std::fprintf(stderr, "training neutral <-> %s on %zu + %zu vectors\n", to_string(emotion), x.size(), y.size());
  const auto start = std::chrono::steady_clock::now();
  const CycleGanModels m = train_cyclegan(x, y, options, [](int it, double lg, double ld) {
    std::fprintf(stderr, "  iteration %5d  generator loss %.4f  discriminator loss %.4f\n", it, lg, ld);
  });
  ensure_writable_dir(out);
  write_mlp(out / "G.fcnn", m.g);
  write_mlp(out / "F.fcnn", m.f);
  write_mlp(out / "DX.fcnn", m.d_x);
  write_mlp(out / "DY.fcnn", m.d_y);
  const Eigen::VectorXf mx = mean(x), my = mean(y);
  nlohmann::json means = {{"neutral", std::vector<float>(mx.data(), mx.data() + mx.size())},
                          {"emotion", std::vector<float>(my.data(), my.data() + my.size())}};
  write_text_file(out / "means.json", means.dump() + "\n");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json meta = {{"from", "neutral"},
                         {"to", to_string(emotion)},
                         {"training_data", source},
                         {"neutral_vectors", x.size()},
                         {"emotion_vectors", y.size()},
                         {"iterations", options.iterations},
                         {"batch_size", options.batch_size},
                         {"learning_rate", options.learning_rate},
                         {"beta1", options.beta1},
                         {"cycle_weight", options.cycle_weight},
                         {"seed", options.seed},
                         {"final_cycle_loss", m.final_cycle_loss},
                         {"seconds", seconds}};
  write_text_file(out / "meta.json", meta.dump(2) + "\n");
  std::fprintf(stderr, "  wrote %s (%.0f s, cycle loss %.4f)\n", out.string().c_str(), seconds, m.final_cycle_loss);
}

}  // namespace

struct RealFrames {
  Emotion emotion;
  std::string csv;
  double from = 0, to = 0;
};

// EMOTION=frames.csv@FROM-TO
RealFrames parse_real_frames(const std::string& spec) {
  const auto eq = spec.find('='), at = spec.rfind('@');
  const auto dash = at == std::string::npos ? std::string::npos : spec.find('-', at);
  const auto bad = [&] { return Error("--real " + spec + ": expected EMOTION=frames.csv@FROM-TO (seconds)"); };
  if (eq == std::string::npos || at == std::string::npos || dash == std::string::npos || at < eq) throw bad();
  RealFrames r;
  const auto e = parse_emotion(spec.substr(0, eq));
  if (!e || *e == Emotion::kNeutral) throw bad();
  r.emotion = *e;
  r.csv = spec.substr(eq + 1, at - eq - 1);
  try {
    r.from = std::stod(spec.substr(at + 1, dash - at - 1));
    r.to = std::stod(spec.substr(dash + 1));
  } catch (const std::exception&) {
    throw bad();
  }
  if (!(r.to > r.from)) throw bad();
  return r;
}

int main(int argc, char** argv) {
  CLI::App app{"facecap-train: expression-mapping training (CycleGAN on blendshape weights, LibTorch)"};
  app.require_subcommand(1);
  std::string model_dir;
  app.add_option("--model-dir", model_dir, "ICT face model folder (for the expression names)");

  auto* dataset = app.add_subcommand("expr-dataset",
                                     "Build the training set: tracked neutral speech from frames.csv files, plus "
                                     "FACS-prototype samples of each emotion laid over it");
  std::vector<std::string> neutral;
  std::string dataset_out;
  int per_emotion = 3000;
  uint64_t seed = 1;
  dataset->add_option("--neutral", neutral, "frames.csv files of `facecap track` on neutral talking footage")
      ->required();
  dataset->add_option("--per-emotion", per_emotion, "Samples per emotion")->capture_default_str();
  std::vector<std::string> real;
  dataset->add_option("--real", real,
                      "Tracked real frames of an emotion: EMOTION=frames.csv@FROM-TO (seconds), e.g. "
                      "happiness=smiles/frames.csv@10-19.7; repeated to make up --real-share of that domain");
  double real_share = 0.15;
  dataset->add_option("--real-share", real_share, "Share of an emotion's samples that real frames make up")
      ->check(CLI::Range(0.0, 0.9))
      ->capture_default_str();
  dataset->add_option("--seed", seed, "Random seed")->capture_default_str();
  dataset->add_option("-o,--output", dataset_out, "Output CSV")->required();

  auto* expr = app.add_subcommand("expr", "Train one mapping: DATA.csv --from neutral --to EMOTION -o MODEL");
  std::string data_csv, from = "neutral", to, out;
  CycleGanOptions options;
  expr->add_option("DATA", data_csv, "Training CSV: a label, then the 53 weights")->required();
  expr->add_option("--from", from, "Source domain")->capture_default_str();
  expr->add_option("--to", to, "Target domain")->required();
  expr->add_option("-o,--output", out, "Model folder (G, F, DX, DY networks, means, meta)")->required();
  expr->add_option("--iterations", options.iterations, "Training iterations")->capture_default_str();
  expr->add_option("--seed", options.seed, "Random seed")->capture_default_str();

  auto* all = app.add_subcommand("expr-all", "Train neutral <-> each of the six emotions: DATA.csv -o MODELS_DIR");
  std::string all_data, all_out;
  all->add_option("DATA", all_data, "Training CSV")->required();
  all->add_option("-o,--output", all_out, "Folder for neutral-<emotion>/ models")->required();
  all->add_option("--iterations", options.iterations, "Training iterations per mapping")->capture_default_str();

  try {
    app.parse(argc, argv);
    const FaceModel model = load_face_model(model_dir.empty() ? default_model_dir() : fs::path(model_dir));
    const auto& names = model.expression_names;
    if (*dataset) {
      std::vector<LabeledWeights> rows;
      std::vector<Eigen::VectorXf> speech;
      for (const std::string& csv : neutral) {
        const auto w = read_tracked_weights(csv, names);
        speech.insert(speech.end(), w.begin(), w.end());
      }
      if (speech.empty()) throw Error("the neutral files hold no tracked frames");
      for (const auto& w : speech) rows.push_back({Emotion::kNeutral, w});
      for (Emotion e : all_emotions()) {
        const auto samples = make_emotion_samples(e, speech, names, per_emotion, seed);
        rows.insert(rows.end(), samples.begin(), samples.end());
      }
      for (const std::string& spec : real) {
        const RealFrames r = parse_real_frames(spec);
        const auto w = read_tracked_weights(r.csv, names, r.from, r.to);
        if (w.empty()) throw Error("--real " + spec + ": no tracked frames in that time range");
        const int repeat =
            std::max(1, static_cast<int>(std::lround(real_share / (1 - real_share) * per_emotion / w.size())));
        for (int k = 0; k < repeat; ++k)
          for (const auto& x : w) rows.push_back({r.emotion, x});
        std::fprintf(stderr, "%s: %zu real frames x %d\n", to_string(r.emotion), w.size(), repeat);
      }
      write_dataset_csv(dataset_out, rows, names);
      std::fprintf(stderr, "wrote %s: %zu neutral rows, %d per emotion\n", dataset_out.c_str(), speech.size(),
                   per_emotion);
    } else if (*expr) {
      const auto f = parse_emotion(from), t = parse_emotion(to);
      if (!f || !t)
        throw Error("--from and --to must be one of neutral, anger, disgust, fear, happiness, sadness, surprise");
      if ((*f == Emotion::kNeutral) == (*t == Emotion::kNeutral)) {
        throw Error("one side of a mapping must be neutral (other pairs relay through neutral)");
      }
      const Emotion emotion = *f == Emotion::kNeutral ? *t : *f;
      train_pair(read_dataset_csv(data_csv, names), emotion, out, options, fs::path(data_csv).filename().string());
    } else {
      const auto data = read_dataset_csv(all_data, names);
      for (Emotion e : all_emotions()) {
        train_pair(data, e, fs::path(all_out) / (std::string("neutral-") + to_string(e)), options,
                   fs::path(all_data).filename().string());
      }
    }
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // usage errors exit with 2, as facecap's do
  } catch (const Error& e) {
    std::fprintf(stderr, "facecap-train: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
