#include "facecap/pipeline/track_each_image.hpp"

#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "facecap/core/atomic_file.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/interrupt.hpp"
#include "facecap/core/progress.hpp"
#include "facecap/io/input.hpp"
#include "facecap/pipeline/action_unit_table.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

// A field as RFC 4180 writes it: quoted where it holds a comma, a quote or a
// line break (a file name may), its quotes doubled.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

// Each image's folder: its name without the extension, or with the
// extension after an underscore where two images share a name; a number
// after that where even those meet.
std::vector<std::string> image_folder_names(const std::vector<fs::path>& images) {
  std::map<std::string, int> stems;
  for (const fs::path& image : images) ++stems[image.stem().string()];
  std::set<std::string> taken;
  std::vector<std::string> names;
  for (const fs::path& image : images) {
    std::string name = image.stem().string();
    if (stems[name] > 1) name += "_" + image.extension().string().substr(1);
    const std::string base = name;
    for (int k = 2; taken.contains(name); ++k) name = base + "_" + std::to_string(k);
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

std::vector<std::string> file_lines(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// frames.csv's fields of one capture without frame, time and shot (the
// first two and the last): what an image's row shares with it.
std::vector<std::string> image_fields(const std::string& frames_csv_line) {
  const std::vector<std::string> all = split_csv_line(frames_csv_line);
  if (all.size() < 4) throw Error("unexpected frames.csv line: " + frames_csv_line);
  return {all.begin() + 2, all.end() - 1};
}

}  // namespace

EachImageSummary run_track_each_image(const FaceModel& model, const fs::path& folder, const fs::path& output_dir,
                                      const TrackOptions& options) {
  if (!fs::is_directory(folder))
    throw Error("--each-image takes a folder of images, and " + folder.string() + " is none");
  const std::vector<fs::path> images = folder_images(folder);
  const std::vector<std::string> names = image_folder_names(images);
  FoldersMadeHere made(/*with_contents=*/true);  // each image's folder fills as the run goes
  made.add(output_dir);
  ensure_writable_dir(output_dir);
  TrackOptions own = options;
  own.capture.quiet = true;
  std::string row_json;
  own.on_row = [&row_json](const std::string& row) { row_json = row; };

  EachImageSummary summary;
  summary.images = static_cast<int>(images.size());
  const int modes = options.capture.fit.identity_modes;
  std::vector<std::string> header;                 // frames.csv's, as image_fields() keeps it
  std::vector<std::vector<std::string>> csv_rows;  // the image's name, then its fields
  std::string jsonl;
  Progress progress("images", summary.images, options.capture.quiet);
  for (size_t i = 0; i < images.size(); ++i) {
    throw_if_interrupted();
    const std::string file = images[i].filename().string();
    nlohmann::json row;
    std::vector<std::string> fields = {file};
    std::unique_ptr<FrameSource> source;
    try {
      source = open_input(images[i].string());
    } catch (const Error& e) {  // an image that cannot be read is its row's business, not the run's
      row = {{"status", "error"}, {"error", e.what()}};
      fields.push_back("error");
      if (summary.unreadable++ == 0) summary.first_error = e.what();
    }
    if (source) {
      const InputInfo info = source->info();
      const fs::path dir = output_dir / names[i];
      made.add(dir);
      row_json.clear();
      const TrackSummary s = run_track(model, *source, images[i].string(), dir, own);
      const std::vector<std::string> lines = file_lines(dir / "frames.csv");
      if (lines.size() != 2 || row_json.empty()) throw Error("expected one frame in " + (dir / "frames.csv").string());
      if (header.empty()) header = image_fields(lines[0]);
      for (std::string& f : image_fields(lines[1])) fields.push_back(std::move(f));
      row = nlohmann::json::parse(row_json);
      for (const char* key : {"frame", "time", "shot"}) row.erase(key);
      row["folder"] = names[i];
      row["size"] = {info.width, info.height};
      const IdentityEstimate& id = s.capture.identity;
      if (s.capture.lost < s.capture.frames) {
        ++summary.with_face;
        row["identity_weights"] = std::vector<double>(id.identity.data(), id.identity.data() + id.identity.size());
        row["focal_px"] = id.focal;
        for (Eigen::Index k = 0; k < id.identity.size() && k < modes; ++k) fields.push_back(csv_number(id.identity[k]));
        if (options.action_units) {  // the units after the identity, as the header has them
          const std::vector<std::string> units = file_lines(dir / "action_units.csv");
          if (units.size() != 2) throw Error("expected one frame in " + (dir / "action_units.csv").string());
          const std::vector<std::string> unit_fields = split_csv_line(units[1]);
          fields.resize(1 + header.size() + size_t(modes));
          fields.insert(fields.end(), unit_fields.begin() + 3, unit_fields.end());  // after frame, time, status
        }
      }
    }
    row["image"] = file;
    jsonl += row.dump() + "\n";
    csv_rows.push_back(std::move(fields));
    progress.update(static_cast<int>(i) + 1);
  }
  progress.finish();
  throw_if_interrupted();

  // Every row as wide as the header: a lost or unreadable image's fields
  // stop where its frames.csv row (or its status) does. Where no image could
  // be read, there is no frames.csv header to take, only the status.
  if (header.empty()) header = {"status"};
  std::string csv = "image";
  for (const std::string& h : header) csv += "," + h;
  for (int k = 0; k < modes; ++k) csv += ",id_" + std::to_string(k);
  const std::vector<std::string> unit_columns =
      options.action_units ? action_unit_columns() : std::vector<std::string>{};
  for (const std::string& column : unit_columns) csv += "," + column;
  csv += "\n";
  const size_t width = 1 + header.size() + size_t(modes) + unit_columns.size();
  for (const std::vector<std::string>& fields : csv_rows) {
    csv += csv_field(fields[0]);
    for (size_t k = 1; k < width; ++k) csv += "," + (k < fields.size() ? fields[k] : std::string());
    csv += "\n";
  }
  summary.tables = {output_dir / "images.csv", output_dir / "images.jsonl"};
  write_text_file(summary.tables[0], csv);
  write_text_file(summary.tables[1], jsonl);
  made.keep();
  return summary;
}

}  // namespace facecap
