#include "facecap/io/video_writer.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <vector>

#include "facecap/core/error.hpp"

extern char** environ;

namespace facecap {

namespace fs = std::filesystem;

std::string video_container(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".mp4" || ext == ".m4v") return "mp4";
  if (ext == ".mov") return "mov";
  if (ext == ".mkv") return "matroska";
  throw Error("cannot write a video to " + path.string() + ": its name must end in .mp4, .m4v, .mov or .mkv");
}

VideoWriter::VideoWriter(const fs::path& path, VideoWriterOptions options)
    : path_(path), options_(std::move(options)), file_(path) {
  const std::string container = video_container(path);
  check_encoding(options_.encoding);
  if (options_.width <= 0 || options_.height <= 0) throw Error("video writer: frame size not set");
  // yuv420p needs even sizes; odd inputs are padded by one pixel.
  options_.width += options_.width % 2;
  options_.height += options_.height % 2;
  if (options_.fps <= 0) options_.fps = 30.0;
  log_path_ = file_.temp_path();
  log_path_ += ".log";
  log_registered_.emplace(log_path_);

  std::vector<std::string> args{"ffmpeg",
                                "-hide_banner",
                                "-loglevel",
                                "error",
                                "-y",
                                "-f",
                                "rawvideo",
                                "-pix_fmt",
                                "yuv420p",
                                "-s",
                                std::to_string(options_.width) + "x" + std::to_string(options_.height),
                                "-r",
                                std::to_string(options_.fps),
                                "-i",
                                "-"};
  const bool audio = options_.audio_source.has_value();
  if (audio) {
    if (options_.audio_start > 0) args.insert(args.end(), {"-ss", std::to_string(options_.audio_start)});
    args.insert(args.end(), {"-i", options_.audio_source->string(), "-map", "0:v:0", "-map", "1:a:0?", "-c:a", "aac",
                             "-b:a", "160k"});
    if (options_.audio_ends_with_video) args.push_back("-shortest");
  }
  args.insert(args.end(), {"-c:v", "libx264", "-preset", options_.encoding.preset, "-crf",
                           std::to_string(options_.encoding.crf), "-pix_fmt", "yuv420p"});
  if (container != "matroska") args.insert(args.end(), {"-movflags", "+faststart+use_metadata_tags"});
  for (const auto& [key, value] : options_.metadata) args.insert(args.end(), {"-metadata", key + "=" + value});
  args.insert(args.end(), {"-f", container, file_.temp_path().string()});

  int fds[2];
  if (::pipe(fds) != 0) throw Error("cannot start ffmpeg: pipe failed");
  ::fcntl(fds[1], F_SETFD, FD_CLOEXEC);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[0]);
  if (rc != 0) {
    ::close(fds[1]);
    throw Error("cannot start ffmpeg (is the ffmpeg package installed?)");
  }
  pid_ = pid;
  pipe_fd_ = fds[1];
  // A frame in a few writes rather than some 40 of the default 64 KB, each
  // a wake-up of both processes: `bench swap` at 720p, 13.6-14.2 -> 14.5-15.1
  // fps end to end. Where the system allows less, the default stays.
  ::fcntl(pipe_fd_, F_SETPIPE_SZ, 1 << 20);
  // A dead encoder must surface as an error from write(), not kill us with SIGPIPE.
  ::signal(SIGPIPE, SIG_IGN);
}

VideoWriter::~VideoWriter() {
  if (!finished_) stop_encoder(true);
  std::error_code ec;
  fs::remove(log_path_, ec);
}

std::string VideoWriter::encoder_log() const {
  std::ifstream in(log_path_);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  // The log sits beside the output: a full disk leaves it empty too.
  return last.empty() ? full_disk_note(path_) : last;
}

namespace {

// A frame of the writer's size: odd sizes padded by one replicated
// row/column for yuv420p, other sizes resized.
cv::Mat fitted_to(const cv::Mat& bgr, int width, int height) {
  if (bgr.type() != CV_8UC3) throw Error("video writer: frames must be 8-bit BGR");
  const int pad_x = width - bgr.cols;
  const int pad_y = height - bgr.rows;
  if (pad_x == 0 && pad_y == 0) return bgr;
  cv::Mat fitted;
  if (pad_x >= 0 && pad_x <= 1 && pad_y >= 0 && pad_y <= 1) {
    cv::copyMakeBorder(bgr, fitted, 0, pad_y, 0, pad_x, cv::BORDER_REPLICATE);
  } else {
    cv::resize(bgr, fitted, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  }
  return fitted;
}

// The frame as the encoder reads it: planar YUV 4:2:0 (BT.601, limited
// range, as ffmpeg's own conversion of BGR makes it, each level within one).
// Converted here, it is half the bytes down the pipe, and ffmpeg's
// conversion cost more than OpenCV's: 144 720p frames at x264's veryfast
// took 1.95 s of the encoder's CPU from BGR, 1.56 s from YUV, against
// 0.08 s for cv::cvtColor.
cv::Mat encoder_frame(const cv::Mat& bgr, int width, int height) {
  cv::Mat yuv;
  cv::cvtColor(fitted_to(bgr, width, height), yuv, cv::COLOR_BGR2YUV_I420);
  return yuv;
}

}  // namespace

void VideoWriter::write(const cv::Mat& bgr) {
  if (pipe_fd_ < 0) throw Error("video writer for " + path_.string() + " is closed");
  send(encoder_frame(bgr, options_.width, options_.height));
}

void VideoWriter::write(const cv::Mat& bgr, double time) {
  if (pipe_fd_ < 0) throw Error("video writer for " + path_.string() + " is closed");
  const cv::Mat yuv = encoder_frame(bgr, options_.width, options_.height);
  if (last_.empty()) first_time_ = time;
  const long long slot = std::llround((time - first_time_) * options_.fps);
  if (!last_.empty() && slot < frames_) return;  // its slot is taken
  while (!last_.empty() && frames_ < slot) send(last_);
  send(yuv);
  last_ = yuv;
}

void VideoWriter::send(const cv::Mat& yuv) {
  const char* data = reinterpret_cast<const char*>(yuv.data);
  size_t left = yuv.total() * yuv.elemSize();
  while (left > 0) {
    const ssize_t n = ::write(pipe_fd_, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string why = encoder_log();
      stop_encoder(true);
      throw Error("ffmpeg stopped while writing " + path_.string() + (why.empty() ? "" : ": " + why));
    }
    data += n;
    left -= static_cast<size_t>(n);
  }
  ++frames_;
}

void VideoWriter::stop_encoder(bool kill) {
  if (pipe_fd_ >= 0) {
    ::close(pipe_fd_);
    pipe_fd_ = -1;
  }
  if (pid_ > 0) {
    if (kill) ::kill(pid_, SIGTERM);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
  }
}

void VideoWriter::finish() {
  if (finished_) return;
  if (frames_ == 0) {
    stop_encoder(true);
    throw Error("no frames were written to " + path_.string());
  }
  ::close(pipe_fd_);
  pipe_fd_ = -1;
  int status = 0;
  rusage usage{};
  while (::wait4(pid_, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  encoder_cpu_ms_ = 1e3 * double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                    1e-3 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw Error("ffmpeg failed to write " + path_.string() + ": " + encoder_log());
  }
  file_.commit();
  finished_ = true;
}

namespace {
constexpr double kStillsFps = 25.0;  // a folder's frames, one after another
}  // namespace

double output_time(const InputInfo& input, int index, double time) {
  return has_timeline(input) ? time : index / (input.fps > 0 ? input.fps : kStillsFps);
}

VideoWriterOptions output_like(const InputInfo& input, int max_frames, const VideoEncoding& encoding) {
  VideoWriterOptions o;
  o.encoding = encoding;
  o.width = input.width;
  o.height = input.height;
  o.fps = input.fps > 0 ? input.fps : kStillsFps;
  if (input.audio) {
    o.audio_source = std::filesystem::path(input.spec);
    o.audio_start = start_time(input);
    // Only where the run stops before the input's end: a whole run keeps the
    // audio's tail past the last frame, as the input has it.
    o.audio_ends_with_video = max_frames > 0 && (input.frames < 0 || input.first_frame + max_frames < input.frames);
  }
  return o;
}

}  // namespace facecap
