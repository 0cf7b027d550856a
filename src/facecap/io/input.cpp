#include "facecap/io/input.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "facecap/core/error.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/input_damage.hpp"
#include "facecap/io/video_decoder.hpp"

namespace facecap {

namespace fs = std::filesystem;

cv::Mat image_or_black(const Frame& frame, const InputInfo& info) {
  return frame.image.empty() ? cv::Mat(info.height, info.width, CV_8UC3, cv::Scalar::all(0)) : frame.image;
}

const char* to_string(InputKind kind) {
  switch (kind) {
    case InputKind::kVideo:
      return "video";
    case InputKind::kImage:
      return "image";
    case InputKind::kImageFolder:
      return "image_folder";
    case InputKind::kCamera:
      return "camera";
  }
  return "video";
}

bool is_image_path(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif" || ext == ".tiff" ||
         ext == ".webp" || ext == ".ppm" || ext == ".pgm";
}

std::vector<fs::path> folder_images(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && is_image_path(entry.path())) files.push_back(entry.path());
  if (files.empty()) throw Error("input folder holds no images: " + dir.string());
  std::sort(files.begin(), files.end());
  return files;
}

namespace {

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g s", seconds);
  return text;
}

}  // namespace

void FrameSource::seek(double seconds) {
  if (seconds == 0) return;
  throw Error("cannot start " + info().spec + " at " + seconds_text(seconds) + ": only a video file has a timeline (" +
              to_string(info().kind) + ")");
}

namespace {

class ImageSource final : public FrameSource {
 public:
  explicit ImageSource(const fs::path& path) {
    image_ = read_image(path);
    if (image_.empty()) throw Error("cannot decode image " + path.string() + ": not an image or corrupt");
    info_.spec = path.string();
    info_.kind = InputKind::kImage;
    info_.width = image_.cols;
    info_.height = image_.rows;
    info_.frames = 1;
  }
  const InputInfo& info() const override { return info_; }
  bool read(Frame& frame) override {
    if (done_) return false;
    done_ = true;
    frame = Frame{image_, 0, 0.0, {}};
    return true;
  }

 private:
  InputInfo info_;
  cv::Mat image_;
  bool done_ = false;
};

class FolderSource final : public FrameSource {
 public:
  explicit FolderSource(const fs::path& dir) : files_(folder_images(dir)) {
    info_.spec = dir.string();
    info_.kind = InputKind::kImageFolder;
    info_.frames = static_cast<int>(files_.size());
    // The first readable image sets the frame size.
    for (const auto& f : files_) {
      const cv::Mat first = read_image(f);
      if (!first.empty()) {
        info_.width = first.cols;
        info_.height = first.rows;
        break;
      }
    }
    if (info_.width == 0) throw Error("no image in folder " + dir.string() + " can be decoded");
  }
  const InputInfo& info() const override { return info_; }
  bool read(Frame& frame) override {
    if (next_ >= files_.size()) return false;
    const fs::path& f = files_[next_];
    frame = Frame{read_image(f), static_cast<int>(next_), 0.0, {}};
    if (frame.image.empty()) {
      frame.error = "cannot decode image " + f.string();
    } else if (frame.image.cols != info_.width || frame.image.rows != info_.height) {
      // The camera model (principal point at the image centre, one focal
      // length) is the folder's: an image of another size is another camera.
      frame.error = "image " + f.string() + " is " + std::to_string(frame.image.cols) + "x" +
                    std::to_string(frame.image.rows) + ", the folder's first is " + std::to_string(info_.width) + "x" +
                    std::to_string(info_.height) + ": a folder is read as one camera's frames";
      frame.image.release();
    }
    ++next_;
    return true;
  }

 private:
  InputInfo info_;
  std::vector<fs::path> files_;
  size_t next_ = 0;
};

class VideoSource final : public FrameSource {
 public:
  // `info` from the container probe (file) or filled here (camera).
  VideoSource(VideoDecoder decoder, InputInfo info) : decoder_(std::move(decoder)), info_(std::move(info)) {
    // Decode the first frame now: a file that opens but cannot decode fails here, not mid-run.
    if (!decoder_.read(first_) || first_.empty()) {
      const int refused = decoder_.refused_packets();
      const std::string why = joined_notes(
          {decoder_.early_end(), refused > 0 ? "the decoder refused " + std::to_string(refused) +
                                                   " packet(s) of it: a corrupt stream, or one it does not support"
                                             : ""});
      throw Error("cannot decode " + info_.spec + ": no frame could be decoded (" +
                  (why.empty() ? "corrupt or unsupported video" : why) + ")");
    }
    first_damaged_ = decoder_.damaged();
    first_time_ = frame_time(0, true);
    info_.width = first_.cols;
    info_.height = first_.rows;
    if (info_.fps <= 0) info_.fps = decoder_.nominal_fps();
    if (info_.fps <= 0 || info_.fps > 1000) info_.fps = 30.0;
  }
  const InputInfo& info() const override { return info_; }

  // The first frame whose time is at or after `seconds`, with its index in
  // display order (video_decoder.hpp): the same pixels, index and time as a
  // read from the start gives there, at a constant rate or not.
  void seek(double seconds) override {
    if (seconds == 0) return;
    if (info_.kind != InputKind::kVideo) FrameSource::seek(seconds);
    if (!std::isfinite(seconds) || seconds < 0) throw Error("a start time must be 0 or more seconds");
    if (index_ != 0 || first_.empty()) throw Error("cannot seek " + info_.spec + " after reading from it");
    const std::string past_end =
        "cannot start " + info_.spec + " at " + seconds_text(seconds) + ": " +
        (info_.duration > 0 ? "it is " + seconds_text(info_.duration) + " long" : std::string("it ends before then"));
    const int index = decoder_.seek(seconds);
    if (index < 0 || !decoder_.read(first_) || first_.empty()) throw Error(past_end);
    first_damaged_ = decoder_.damaged();
    index_ = index;
    info_.first_frame = index;
    first_time_ = info_.first_time = frame_time(index, true);
  }

  bool read(Frame& frame) override {
    cv::Mat image;
    double time = 0;
    bool damaged = false;
    if (!first_.empty()) {
      image = first_;
      first_.release();
      time = first_time_;
      damaged = first_damaged_;
    } else if (!decoder_.read(image) || image.empty()) {
      return false;
    } else {
      time = frame_time(index_, false);
      damaged = decoder_.damaged();
    }
    frame = Frame{image, index_, time, {}, damaged};
    previous_time_ = time;
    ++index_;
    return true;
  }

  std::string early_end() const override { return decoder_.early_end(); }
  int refused_packets() const override { return decoder_.refused_packets(); }

 private:
  // The time of the frame just decoded, index `index`: a file's timestamp
  // from the stream's start, unless it is missing or, after the first frame
  // read, does not move forward (broken timestamps), where the frame is taken
  // to follow the last by 1 / fps; a camera's index / fps.
  double frame_time(int index, bool first) const {
    const double nominal = index / info_.fps;
    if (info_.kind != InputKind::kVideo) return nominal;
    const double pts = decoder_.time();
    if (std::isfinite(pts) && pts >= 0 && (first || pts > previous_time_)) return pts;
    return first ? nominal : previous_time_ + 1.0 / info_.fps;
  }

  VideoDecoder decoder_;
  InputInfo info_;
  cv::Mat first_;
  bool first_damaged_ = false;
  double first_time_ = 0;
  double previous_time_ = -1;  // the last frame read's time (-1: none yet)
  int index_ = 0;
};

// The input as it opens, at its first frame.
std::unique_ptr<FrameSource> open_source(const std::string& spec) {
  if (spec.rfind("cam:", 0) == 0) {
    int id = -1;
    try {
      id = std::stoi(spec.substr(4));
    } catch (const std::exception&) {
      throw Error("bad camera input '" + spec + "': use cam:N with N a camera number");
    }
    VideoDecoder camera = VideoDecoder::open_camera(id);
    InputInfo info;
    info.spec = spec;
    info.kind = InputKind::kCamera;
    info.fps = camera.nominal_fps();
    return std::make_unique<VideoSource>(std::move(camera), info);
  }
  const fs::path path(spec);
  std::error_code ec;
  if (spec.empty()) throw Error("no input given");
  if (!fs::exists(path, ec)) throw Error("input not found: " + spec);
  if (fs::is_directory(path, ec)) return std::make_unique<FolderSource>(path);
  if (!fs::is_regular_file(path, ec)) throw Error("input is not a regular file: " + spec);
  if (fs::file_size(path, ec) == 0) throw Error("input is empty (0 bytes): " + spec);
  if (is_image_path(path)) return std::make_unique<ImageSource>(path);
  VideoDecoder decoder = VideoDecoder::open_file(path);
  const InputInfo info = decoder.facts();
  return std::make_unique<VideoSource>(std::move(decoder), info);
}

}  // namespace

std::unique_ptr<FrameSource> open_input(const std::string& spec, double start_seconds) {
  std::unique_ptr<FrameSource> source = open_source(spec);
  source->seek(start_seconds);
  return source;
}

}  // namespace facecap
