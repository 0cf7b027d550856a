// TrackJob end to end on real footage: its files, a Live Link take, a given
// identity, a start part-way, gaze, lost frames, the refinement's outputs
// and bad input.
#include "facecap/pipeline/track_job.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "app/command.hpp"
#include "facecap/core/csv_line.hpp"
#include "facecap/core/error.hpp"
#include "facecap/core/temp_dir.hpp"
#include "facecap/expr/action_units.hpp"
#include "facecap/io/image_file.hpp"
#include "facecap/io/input.hpp"
#include "facecap/io/livelink_face.hpp"
#include "facecap/io/png16.hpp"
#include "facecap/model/regions.hpp"
#include "facecap/pipeline/face_animation.hpp"
#include "facecap/pipeline/face_matte.hpp"
#include "facecap/pipeline/frame_files.hpp"
#include "facecap/pipeline/identity_file.hpp"
#include "io/glb_reader.hpp"
#include "io/livelink_receiver.hpp"
#include "test_support.hpp"

namespace facecap {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> lines(const fs::path& p) { return test::read_lines(p); }

int count_fields(const std::string& line) { return static_cast<int>(std::count(line.begin(), line.end(), ',')) + 1; }

// `seconds` of a file's audio from `start`, mono at 8 kHz, through ffmpeg.
std::vector<float> audio_samples(const fs::path& file, double start, double seconds) {
  const std::string command = "ffmpeg -v error -ss " + std::to_string(start) + " -t " + std::to_string(seconds) +
                              " -i '" + file.string() + "' -ac 1 -ar 8000 -f s16le -";
  std::vector<float> out;
  FILE* pipe = ::popen(command.c_str(), "r");
  int16_t sample = 0;
  while (pipe && std::fread(&sample, sizeof(sample), 1, pipe) == 1) out.push_back(sample);
  if (pipe) ::pclose(pipe);
  return out;
}

// Normalised correlation of two equally long signals.
double correlation(const std::vector<float>& a, const std::vector<float>& b) {
  const size_t n = std::min(a.size(), b.size());
  double ab = 0, aa = 0, bb = 0;
  for (size_t i = 0; i < n; ++i) {
    ab += double(a[i]) * b[i];
    aa += double(a[i]) * a[i];
    bb += double(b[i]) * b[i];
  }
  return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0.0;
}

// The first `count` frames of `video` as an image folder, frame `blank` grey
// (no face in it).
void write_frames_with_a_blank(const fs::path& video, const fs::path& folder, int count, int blank) {
  auto source = open_input(video.string());
  Frame f;
  for (int i = 0; i < count && source->read(f); ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "f%03d.png", i);
    cv::Mat img = f.image;
    if (i == blank) img = cv::Mat(img.size(), img.type(), cv::Scalar(60, 60, 60));
    facecap::write_image((folder / name).string(), img);
  }
}

}  // namespace

TEST(TrackJob, WritesCsvJsonlIdentityMeshesAndOverlay) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  TrackOptions o;
  o.capture.quiet = true;
  o.capture.max_frames = 36;
  o.meshes = true;
  o.overlay = true;
  // An earlier, longer run's mesh in the folder, and a file of the user's.
  fs::create_directories(dir.path() / "meshes");
  std::ofstream(dir.path() / "meshes" / "frame_000050.obj") << "v 0 0 0\n";
  std::ofstream(dir.path() / "meshes" / "notes.txt") << "mine\n";
  const TrackSummary s = run_track(*model, video.string(), dir.path(), o);
  EXPECT_EQ(s.capture.frames, 36);

  const auto csv = lines(dir.path() / "frames.csv");
  ASSERT_EQ(csv.size(), 37u);
  EXPECT_EQ(count_fields(csv[0]), 14 + 53 + 9 + 1);
  EXPECT_NE(csv[0].find(",jawOpen,"), std::string::npos);
  EXPECT_TRUE(csv[0].ends_with(",iris_left_y,shot")) << csv[0];
  EXPECT_NE(csv[0].find(",gaze_yaw_deg,gaze_pitch_deg,"), std::string::npos);
  for (size_t i = 1; i < csv.size(); ++i) {
    EXPECT_EQ(count_fields(csv[i]), 14 + 53 + 9 + 1) << "row " << i;
    EXPECT_TRUE(csv[i].ends_with(",0")) << "row " << i;  // one shot
    EXPECT_EQ(csv[i].find("nan"), std::string::npos) << "row " << i;
  }
  const auto jsonl = lines(dir.path() / "frames.jsonl");
  ASSERT_EQ(jsonl.size(), 36u);
  const auto row = nlohmann::json::parse(jsonl[10]);
  EXPECT_EQ(row["frame"], 10);
  EXPECT_EQ(row["weights"].size(), 53u);
  EXPECT_EQ(row["landmarks"].size(), 68u);

  std::ifstream id_in(dir.path() / "identity.json");
  const auto id = nlohmann::json::parse(id_in);
  EXPECT_EQ(id["identity_weights"].size(), 50u);
  EXPECT_GT(id["focal_px"].get<double>(), 100.0);

  // One sequence: this run's meshes, the earlier run's gone, the user's file kept.
  int meshes = 0;
  for (const auto& e : fs::directory_iterator(dir.path() / "meshes")) meshes += e.path().extension() == ".obj";
  EXPECT_EQ(meshes, 36 - s.capture.lost);
  EXPECT_FALSE(fs::exists(dir.path() / "meshes" / "frame_000050.obj"));
  EXPECT_TRUE(fs::exists(dir.path() / "meshes" / "notes.txt"));
  const auto obj = lines(dir.path() / "meshes" / "frame_000000.obj");
  EXPECT_GT(std::count_if(obj.begin(), obj.end(), [](const std::string& l) { return l.rfind("vt ", 0) == 0; }), 1000);
  EXPECT_EQ(open_input((dir.path() / "overlay.mp4").string())->info().frames, 36);
}

// --livelink: a Live Link Face take with a row per frame, its weights those
// of frames.csv under ARKit's names, its head angles frames.csv's in radians;
// a lost frame holds the last tracked one's values.
TEST(TrackJob, WritesALiveLinkFaceTakeOfTheCapture) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  const fs::path clip = dir.path() / "dark.mp4";
  const test::CommandResult made = test::run_command(
      "ffmpeg -nostdin -hide_banner -loglevel error -y -i " + video.string() +
      " -vf \"trim=end_frame=40,drawbox=x=0:y=0:w=iw:h=ih:color=black:t=fill:enable='between(n,34,39)'\" -an -c:v "
      "libx264 -preset ultrafast -crf 16 " +
      clip.string() + " 2>&1");
  ASSERT_EQ(made.code, 0) << made.out;
  TrackOptions o;
  o.capture.quiet = true;
  o.livelink = true;
  // --livelink-udp: the same values, live, one datagram a frame.
  const test::UdpReceiver receiver;
  o.livelink_stream.emplace();
  o.livelink_stream->target = {"127.0.0.1", receiver.port()};
  o.livelink_stream->subject = "actor";
  o.livelink_stream->paced = false;
  const TrackSummary s = run_track(*model, clip.string(), dir.path(), o);
  ASSERT_EQ(s.capture.frames, 40);
  EXPECT_EQ(s.livelink_sent, 40);
  EXPECT_EQ(s.livelink_error, "");
  const auto take = lines(dir.path() / "livelink_face.csv");
  const auto csv = lines(dir.path() / "frames.csv");
  ASSERT_EQ(take.size(), 41u);
  ASSERT_EQ(csv.size(), 41u);
  const auto fields = split_csv_line;
  const auto take_header = fields(take[0]), csv_header = fields(csv[0]);
  ASSERT_EQ(take_header.size(), 63u);
  auto column = [](const std::vector<std::string>& header, const std::string& name) {
    return static_cast<size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  int lost = 0;
  std::vector<std::string> last_tracked;
  for (size_t row = 1; row < take.size(); ++row) {
    const auto t = fields(take[row]), c = fields(csv[row]);
    ASSERT_EQ(t.size(), 63u) << row;
    if (c[2] == "lost") {
      ++lost;
      ASSERT_FALSE(last_tracked.empty());
      // The last tracked frame's values, at this frame's time.
      EXPECT_EQ(std::vector<std::string>(t.begin() + 1, t.end()),
                std::vector<std::string>(last_tracked.begin() + 1, last_tracked.end()))
          << row;
      continue;
    }
    last_tracked = t;
    for (const char* name : {"JawOpen", "EyeBlinkLeft", "MouthSmileRight"}) {
      std::string ict = name;
      ict[0] = char(std::tolower(ict[0]));
      if (ict.ends_with("Left")) ict = ict.substr(0, ict.size() - 4) + "_L";
      if (ict.ends_with("Right")) ict = ict.substr(0, ict.size() - 5) + "_R";
      EXPECT_NEAR(std::stod(t[column(take_header, name)]), std::stod(c[column(csv_header, ict)]), 1e-5)
          << name << " row " << row;
    }
    EXPECT_NEAR(std::stod(t[column(take_header, "HeadYaw")]),
                std::stod(c[column(csv_header, "yaw_deg")]) * 3.14159265358979 / 180, 1e-5)
        << row;
  }
  EXPECT_EQ(lost, 6);                                 // the black ones
  EXPECT_EQ(fields(take[11])[0], "00:00:00:10.000");  // frame 10 of a 25 fps clip

  // Each datagram holds its frame's row of the take, by name (the stream
  // orders a few apart from the take).
  for (size_t row = 1; row < take.size(); ++row) {
    const auto got = receiver.receive();
    ASSERT_TRUE(got) << "datagram " << row;
    const test::LiveLinkDatagram d = test::decode_livelink(*got);
    EXPECT_EQ(d.version, 6);
    EXPECT_EQ(d.subject, "actor");
    EXPECT_EQ(d.rate_numerator, 25);  // the clip's rate
    ASSERT_EQ(d.values.size(), 61u);
    const auto t = fields(take[row]);
    for (size_t k = 2; k < take_header.size(); ++k)
      EXPECT_NEAR(d.values[LiveLinkFace::index_of(take_header[k])], std::stod(t[k]), 1e-6)
          << take_header[k] << " row " << row;
  }
  EXPECT_FALSE(receiver.receive(100));
}

// --identity: a take captured with the identity of another take of the same
// speaker holds it exactly, and says so; its fit stays good.
TEST(TrackJob, AGivenIdentityIsHeldAndRecorded) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(take_a, "address_720p_a.mp4");
  FACECAP_REQUIRE_DATA(take_b, "address_720p_b.mp4");
  TempDir dir;
  TrackOptions o;
  o.capture.quiet = true;
  o.capture.max_frames = 40;
  run_track(*model, take_a.string(), dir.path() / "a", o);
  o.capture.fit.known_identity = read_identity_weights(dir.path() / "a" / "identity.json");
  const TrackSummary b = run_track(*model, take_b.string(), dir.path() / "b", o);
  EXPECT_EQ(b.capture.lost, 0);
  EXPECT_EQ(b.capture.identity.identity, *o.capture.fit.known_identity);
  std::ifstream in(dir.path() / "b" / "identity.json");
  const nlohmann::json id = nlohmann::json::parse(in);
  EXPECT_EQ(id["identity_given"], true);
  EXPECT_EQ(id["size_correction"]["identity_modes_determined"], 0.0);  // not solved from this take
  EXPECT_EQ(Eigen::Map<const Eigen::VectorXd>(id["identity_weights"].get<std::vector<double>>().data(), 50),
            *o.capture.fit.known_identity);
  for (const std::string& row : lines(dir.path() / "b" / "frames.jsonl"))
    EXPECT_LT(nlohmann::json::parse(row)["landmark_error"].get<double>(), 0.04);
}

// --start: the frames keep the video's numbers and times, and the overlay's
// sound is the video's from that time on.
TEST(TrackJob, StartingPartWayKeepsTheVideosTimelineAndItsSound) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  TempDir dir;
  TrackOptions o;
  o.capture.quiet = true;
  o.capture.start_seconds = 2.0;
  o.capture.max_frames = 24;
  o.overlay = true;
  const TrackSummary s = run_track(*model, video.string(), dir.path(), o);
  EXPECT_EQ(s.capture.frames, 24);
  const double fps = s.capture.input.fps;
  const int first = int(std::ceil(2.0 * fps));  // 60 at 29.97 fps
  const auto csv = lines(dir.path() / "frames.csv");
  ASSERT_EQ(csv.size(), 25u);
  EXPECT_EQ(csv[1].substr(0, csv[1].find(',')), std::to_string(first));
  const auto row = nlohmann::json::parse(lines(dir.path() / "frames.jsonl").back());
  EXPECT_EQ(row["frame"], first + 23);
  EXPECT_NEAR(row["time"].get<double>(), (first + 23) / fps, 1e-3);

  const fs::path overlay = dir.path() / "overlay.mp4";
  const InputInfo info = probe_video_file(overlay);
  EXPECT_EQ(info.frames, 24);
  ASSERT_TRUE(info.audio);
  EXPECT_NEAR(info.audio_duration, 24 / fps, 0.05);
  // The overlay's sound (re-encoded) matches the input's from the first
  // frame's time, not from its beginning nor a tenth of a second off.
  const std::vector<float> out = audio_samples(overlay, 0.0, 0.7);
  ASSERT_GT(out.size(), 5000u);
  const double aligned = correlation(out, audio_samples(video, first / fps, 0.7));
  EXPECT_GT(aligned, 0.9);
  EXPECT_LT(correlation(out, audio_samples(video, 0.0, 0.7)), 0.5 * aligned);
  EXPECT_LT(correlation(out, audio_samples(video, first / fps + 0.1, 0.7)), 0.5 * aligned);
}

// Gaze from the irises on real footage: no gaze truth exists for it, but an
// iris must lie inside its own eye's landmarks, at a size an iris has, and
// the speaker (reading a prompter beside the lens) looks about at the camera.
TEST(TrackJob, GazeComesFromAnIrisInsideEachEye) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "address_720p_a.mp4");
  TempDir dir;
  TrackOptions o;
  o.capture.quiet = true;
  o.capture.max_frames = 40;
  const TrackSummary s = run_track(*model, video.string(), dir.path(), o);
  ASSERT_EQ(s.capture.lost, 0);
  // 88 of the first 90 frames, all 40 of these, have an iris (the other 2 blink).
  EXPECT_GE(s.gaze_frames, 36);
  const auto jsonl = lines(dir.path() / "frames.jsonl");
  ASSERT_EQ(jsonl.size(), 40u);
  int both = 0;
  for (const std::string& line : jsonl) {
    const auto row = nlohmann::json::parse(line);
    if (row["gaze"].is_null()) continue;
    const auto& gaze = row["gaze"];
    EXPECT_LT(std::abs(gaze["yaw_deg"].get<double>()), 25.0) << row["frame"];
    EXPECT_LT(std::abs(gaze["pitch_deg"].get<double>()), 25.0) << row["frame"];
    EXPECT_LT(gaze["direction_camera"][2].get<double>(), -0.8) << row["frame"];  // toward the camera
    both += !gaze["right"].is_null() && !gaze["left"].is_null();
    for (int eye = 0; eye < 2; ++eye) {
      const auto& e = gaze[eye == 0 ? "right" : "left"];
      if (e.is_null()) continue;
      std::vector<cv::Point2f> outline;
      for (int k = 0; k < 6; ++k) {
        const auto& p = row["landmarks"][36 + 6 * eye + k];
        outline.emplace_back(p[0].get<float>(), p[1].get<float>());
      }
      const cv::Point2f iris(e["iris_px"][0].get<float>(), e["iris_px"][1].get<float>());
      // Inside, or on the outline within a pixel: this speaker's upper lids
      // cover the iris's top, and its centre can sit at their edge.
      EXPECT_GE(cv::pointPolygonTest(outline, iris, true), -1.0) << "frame " << row["frame"] << " eye " << eye;
      const double width = cv::norm(outline[3] - outline[0]);
      EXPECT_GT(e["iris_radius_px"].get<double>(), 0.15 * width);
      EXPECT_LT(e["iris_radius_px"].get<double>(), 0.4 * width);
    }
  }
  EXPECT_GE(both, 30);
}

TEST(TrackJob, LostFramesHaveEmptyFieldsAndTrackingResumes) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  // An image folder: 31 face frames, a blank frame, then faces again.
  TempDir frames;
  write_frames_with_a_blank(video, frames.path(), 36, 31);
  TempDir out;
  TrackOptions o;
  o.capture.quiet = true;
  o.gltf = true;
  o.landmarks_csv = true;
  o.action_units = true;
  o.aligned_faces = true;
  o.aligned_face_size = 96;
  o.uv_pass = true;
  o.chan = true;
  // An earlier run's crops of frames this one loses or does not reach go;
  // other files stay. So do its UV passes past this run's end.
  fs::create_directories(out.path() / "aligned");
  for (const char* name : {"frame_000031.png", "frame_000099.png", "notes.txt"})
    std::ofstream(out.path() / "aligned" / name) << "earlier";
  fs::create_directories(out.path() / "uv");
  std::ofstream(out.path() / "uv" / "frame_000099.png") << "earlier";
  const TrackSummary s = run_track(*model, frames.path().string(), out.path(), o);
  const auto csv = lines(out.path() / "frames.csv");
  ASSERT_EQ(csv.size(), 37u);
  // So is the landmark table's row, and the next tracked frame's is whole.
  const auto table = lines(out.path() / "landmarks.csv");
  ASSERT_EQ(table.size(), 37u);
  EXPECT_EQ(table[32], csv[32].substr(0, csv[32].find(",lost,") + 5) + std::string(7 * 68, ','));
  EXPECT_EQ(table[34].find(",,"), std::string::npos) << table[34].substr(0, 80);
  // The action units' too; a tracked row's units are its frames.csv weights,
  // read as action_units.hpp reads them.
  const auto units = lines(out.path() / "action_units.csv");
  const auto jsonl = lines(out.path() / "frames.jsonl");  // no header
  ASSERT_EQ(jsonl.size(), 36u);
  ASSERT_EQ(units.size(), 37u);
  const size_t unit_count = action_units().size();
  EXPECT_EQ(units[32], table[32].substr(0, table[32].find(",lost,") + 5) + std::string(2 * unit_count, ','));
  const std::vector<std::string> header = split_csv_line(csv[0]), unit_header = split_csv_line(units[0]);
  ASSERT_EQ(unit_header.size(), 3 + 2 * unit_count);
  for (int row : {1, 20, 34}) {
    const std::vector<std::string> frame = split_csv_line(csv[row]), unit_row = split_csv_line(units[row]);
    ASSERT_EQ(unit_row.size(), unit_header.size()) << "row " << row;
    EXPECT_EQ(unit_row[0], frame[0]);
    for (size_t u = 0; u < unit_count; ++u) {
      double weight_sum = 0;
      for (const std::string& shape : action_units()[u].shapes)
        weight_sum += std::stod(frame[std::find(header.begin(), header.end(), shape) - header.begin()]);
      const double intensity = std::stod(unit_row[3 + u]);
      EXPECT_NEAR(intensity, 5.0 * weight_sum / double(action_units()[u].shapes.size()), 1e-4)
          << unit_header[3 + u] << ", row " << row;
      EXPECT_EQ(unit_row[3 + unit_count + u], intensity >= 1.0 ? "1" : "0") << unit_header[3 + unit_count + u];
    }
    // frames.jsonl (and so --stream) has the same intensities.
    const nlohmann::json json_row = nlohmann::json::parse(jsonl[row - 1]);
    ASSERT_EQ(json_row["action_units"].size(), unit_count);
    for (size_t u = 0; u < unit_count; ++u)
      EXPECT_NEAR(double(json_row["action_units"][action_units()[u].label()]), std::stod(unit_row[3 + u]), 1e-4);
  }
  EXPECT_FALSE(nlohmann::json::parse(jsonl[31]).contains("action_units"));  // the lost frame
  // A crop for each tracked frame, none for the lost one.
  int crops = 0;
  for (int frame = 0; frame < 36; ++frame) {
    const std::string name = frame_file_name(frame, "png");
    const fs::path crop = out.path() / "aligned" / name;
    const bool tracked = csv[frame + 1].find(",lost,") == std::string::npos;
    ASSERT_EQ(fs::exists(crop), tracked) << name;
    if (!tracked) continue;
    ++crops;
    EXPECT_EQ(read_image(crop.string()).size(), cv::Size(96, 96)) << name;
  }
  EXPECT_EQ(crops, 36 - s.capture.lost);
  // A UV pass for every frame, the input's size; the lost frame's empty,
  // the tracked ones' showing the face.
  EXPECT_EQ(s.uv_passes, 36);
  for (int frame : {30, 31, 34}) {
    const std::string name = frame_file_name(frame, "png");
    const cv::Mat pass = read_png16(out.path() / "uv" / name);
    ASSERT_EQ(pass.type(), CV_16UC4) << name;
    ASSERT_EQ(pass.size(), cv::Size(400, 300)) << name;
    std::vector<cv::Mat> channels;
    cv::split(pass, channels);
    if (frame == 31)
      EXPECT_EQ(cv::countNonZero(pass.reshape(1)), 0) << name;
    else
      EXPECT_GT(cv::countNonZero(channels[3]), 100 * 100) << name;  // the face region covers over 100 x 100 px
  }
  EXPECT_FALSE(fs::exists(out.path() / "uv" / "frame_000099.png"));
  EXPECT_FALSE(fs::exists(out.path() / "aligned" / "frame_000099.png"));
  EXPECT_TRUE(fs::exists(out.path() / "aligned" / "notes.txt"));
  EXPECT_NE(csv[32].find(",lost,,,"), std::string::npos) << csv[32];
  // Every field after the status is empty, gaze included; then the shot.
  EXPECT_EQ(csv[32].substr(csv[32].find(",lost,") + 5), std::string(11 + 53 + 9 + 1, ',') + "0") << csv[32];
  EXPECT_EQ(csv[32].find("nan"), std::string::npos);
  EXPECT_EQ(csv[34].find("lost"), std::string::npos) << csv[34];  // back

  // The animation keys the tracked frames only: players interpolate across the lost one.
  const test::Glb g = test::Glb::read(out.path() / "animation.glb");
  const auto& sampler = g.doc["animations"][0]["samplers"][0];
  const std::vector<float> times = g.floats(sampler["input"]);
  EXPECT_EQ(int(times.size()), 36 - s.capture.lost);
  EXPECT_GE(s.capture.lost, 1);
  // Images have no timeline: they are keyed 1/30 s apart, and frame 31 has no key.
  for (float t : times) EXPECT_GT(std::abs(t - 31 / 30.0), 1e-4);
  EXPECT_NEAR(times.back(), 35 / 30.0, 1e-6);
  EXPECT_EQ(g.doc["meshes"][0]["primitives"][0]["targets"].size(), 53u + 4u);  // + the eye turns
  EXPECT_FALSE(g.doc.contains("textures"));  // no albedo without --refine: the one image is the matte
  ASSERT_EQ(g.doc["images"].size(), 1u);
  EXPECT_EQ(g.doc["images"][0]["name"], kFaceMatteImageName);
  // Beside them, the face matte (face_matte.hpp), listed in the summary.
  EXPECT_EQ(s.face_matte, out.path() / "face_matte.png");
  const cv::Mat matte = read_image((out.path() / "face_matte.png").string());
  ASSERT_EQ(matte.size(), cv::Size(1024, 1024));
  cv::Mat grey;
  cv::extractChannel(matte, grey, 0);
  EXPECT_EQ(cv::countNonZero(grey != face_matte_image(*model)), 0);
  // Put through a frame's UV pass as a compositor's STMap does (u right, v
  // up, texel centres at (i + 0.5) / size), it is the face's matte in that
  // frame: whole at the fitted inner landmarks, and none on part of what the
  // pass covers (the scalp, ears and neck).
  const cv::Mat pass = read_png16(out.path() / "uv" / frame_file_name(30, "png"));
  cv::Mat map_x(pass.size(), CV_32F), map_y(pass.size(), CV_32F), in_frame;
  for (int y = 0; y < pass.rows; ++y)
    for (int x = 0; x < pass.cols; ++x) {
      const cv::Vec<uint16_t, 4> p = pass.at<cv::Vec<uint16_t, 4>>(y, x);
      const bool covered = p[3] > 0;
      map_x.at<float>(y, x) = covered ? p[2] / 65535.0f * grey.cols - 0.5f : -10.0f;
      map_y.at<float>(y, x) = covered ? (1 - p[1] / 65535.0f) * grey.rows - 0.5f : -10.0f;
    }
  cv::remap(grey, in_frame, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::Mat pass_alpha;
  cv::extractChannel(pass, pass_alpha, 3);
  const int region_px = cv::countNonZero(pass_alpha),
            held_out_px = cv::countNonZero((pass_alpha > 0) & (in_frame == 0));
  int whole = 0, landmarks_on_the_face = 0;
  const nlohmann::json fitted = nlohmann::json::parse(jsonl[30])["fitted_landmarks"];
  for (size_t i = 17; i < 68; ++i) {
    const cv::Point px(int(std::lround(double(fitted[i][0]))), int(std::lround(double(fitted[i][1]))));
    if (pass_alpha.at<uint16_t>(px) == 0) continue;  // the inner lips' rim
    ++landmarks_on_the_face;
    whole += in_frame.at<uint8_t>(px) >= 250;
  }
  std::printf("face matte through the UV pass: %d of %d landmarks whole; %d of the region's %d px held out\n", whole,
              landmarks_on_the_face, held_out_px, region_px);
  // The .chan files key the tracked frames only, numbered from 1.
  ASSERT_EQ(s.chan_files, (std::vector<fs::path>{out.path() / "head.chan", out.path() / "camera.chan"}));
  for (const fs::path& chan : s.chan_files) {
    const auto keyed = lines(chan);
    ASSERT_EQ(int(keyed.size()), 36 - s.capture.lost) << chan;
    EXPECT_EQ(keyed.front().rfind("1 ", 0), 0u) << keyed.front();
    for (const std::string& line : keyed) {
      EXPECT_NE(line.rfind("32 ", 0), 0u) << line;  // the lost frame 31
      // frame, translation, rotation, and the camera's field of view
      EXPECT_EQ(std::count(line.begin(), line.end(), ' '), chan == s.chan_files[0] ? 6 : 7) << line;
    }
  }
  EXPECT_GE(landmarks_on_the_face, 40);  // measured 43 (the lips' inner points on the mouth's rim are not)
  EXPECT_EQ(whole, landmarks_on_the_face);
  EXPECT_GT(held_out_px, region_px / 5);  // measured 35 %
}

// --uv-pass on real footage: where the fit puts each inner landmark (iBUG
// 17-67, fixed vertices of the model), the pass shows that vertex's UV, to
// within the UV a pixel spans there (the landmark's pixel centre lies up to
// 0.7 px from the landmark). With --refine (on a 720p clip, refined over two
// levels) the pass is the refined surface's, which lies within a hair of the
// tracked one.
TEST(TrackJob, TheUvPassShowsEachLandmarksUvWhereTheFitPutsIt) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(webcam, "talking_webcam_400x300.mp4");
  FACECAP_REQUIRE_DATA(address, "address_720p_a.mp4");  // refined over two levels
  const std::vector<Vec2f> uvs = per_vertex_uvs(model->region_mesh(regions::kFace));
  for (const bool refine : {false, true}) {
    const fs::path& video = refine ? address : webcam;
    TempDir dir;
    TrackOptions o;
    o.capture.quiet = true;
    o.capture.max_frames = 36;
    o.uv_pass = true;
    o.refine = refine;
    std::vector<std::pair<int, Landmarks>> fitted;
    o.on_frame = [&](const CapturedFrame& f) {
      if (f.status != TrackStatus::kLost && f.index % 10 == 5) fitted.emplace_back(f.index, f.fit.fitted);
    };
    run_track(*model, video.string(), dir.path(), o);
    ASSERT_EQ(fitted.size(), 4u);
    std::vector<double> error_px;
    int uncovered = 0;
    for (const auto& [frame, landmarks] : fitted) {
      const std::string name = frame_file_name(frame, "png");
      const cv::Mat pass = read_png16(dir.path() / "uv" / name);
      ASSERT_EQ(pass.type(), CV_16UC4) << name;
      // The UV a pixel spans here: the outer eye corners' UV distance over their pixel distance.
      const int left = model->landmarks.vertices[36], right = model->landmarks.vertices[45];
      const double uv_per_px = (uvs[right] - uvs[left]).norm() / (landmarks[45] - landmarks[36]).norm();
      for (int i = 17; i < 68; ++i) {
        const cv::Point px(int(std::lround(landmarks[i].x())), int(std::lround(landmarks[i].y())));
        const cv::Vec<uint16_t, 4> p = pass.at<cv::Vec<uint16_t, 4>>(px);
        if (p[3] == 0) {
          ++uncovered;  // the lips' inner points lie on the mouth's rim
          continue;
        }
        const Vec2f uv(p[2] / 65535.0f, p[1] / 65535.0f);
        error_px.push_back((uv - uvs[model->landmarks.vertices[i]]).norm() / uv_per_px);
      }
    }
    std::sort(error_px.begin(), error_px.end());
    const double median_px = error_px[error_px.size() / 2], p90_px = error_px[error_px.size() * 9 / 10];
    std::printf("refine %d: %zu landmarks, %d on no face; error median %.2f px, 90th percentile %.2f px\n", refine,
                error_px.size(), uncovered, median_px, p90_px);
    // Measured: median 0.44 / 0.39 px, 90th percentile 0.98 / 1.11 px (the
    // refined surface's displacements shift it a little, up to 0.6 mm).
    EXPECT_LE(uncovered, 4 * 8);  // at most the 8 inner lip points a frame
    EXPECT_LT(median_px, 0.6);
    EXPECT_LT(p90_px, 1.5);
  }
}

TEST(TrackJob, RefineAddsLightingAlbedoAndRefinedMeshes) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir dir;
  TrackOptions o;
  o.capture.quiet = true;
  o.capture.max_frames = 32;
  o.meshes = true;
  o.overlay = true;
  o.refine = true;
  o.gltf = true;
  const TrackSummary s = run_track(*model, video.string(), dir.path(), o);
  EXPECT_EQ(s.refined_frames, 32 - s.capture.lost);
  const auto csv = lines(dir.path() / "frames.csv");
  ASSERT_EQ(csv.size(), 33u);
  EXPECT_EQ(count_fields(csv[0]), 14 + 53 + 9 + 9 + 1);  // lighting, then gaze, then the shot
  EXPECT_NE(csv[0].find(",l8,gaze_yaw_deg,"), std::string::npos);
  for (size_t i = 1; i < csv.size(); ++i) EXPECT_EQ(csv[i].find("nan"), std::string::npos);
  const cv::Mat albedo = facecap::read_image((dir.path() / "albedo.png").string());
  ASSERT_FALSE(albedo.empty());
  // The animated glTF carries the same albedo as its texture.
  const test::Glb g = test::Glb::read(dir.path() / "animation.glb");
  const auto& view = g.doc["bufferViews"][int(g.doc["images"][0]["bufferView"])];
  EXPECT_EQ(size_t(view["byteLength"]), fs::file_size(dir.path() / "albedo.png"));
  EXPECT_GT(cv::mean(albedo)[2], 20.0);  // skin, not black
  for (const char* video_name : {"overlay.mp4", "shaded.mp4", "heatmap.mp4"}) {
    EXPECT_EQ(open_input((dir.path() / video_name).string())->info().frames, 32) << video_name;
  }
  // What they show: inside the last frame's face (the box of its fitted
  // landmarks, shrunk to its middle half), shaded.mp4 draws the refined
  // surface in light grey over the input dimmed to 0.3, and heatmap.mp4 the
  // error's colours over the input dimmed to 0.4; outside the face, only the
  // dimmed input.
  const auto last_row = nlohmann::json::parse(lines(dir.path() / "frames.jsonl").back());
  ASSERT_EQ(last_row["status"], "tracked");
  cv::Rect2f box;
  {
    std::vector<cv::Point2f> points;
    for (const auto& p : last_row["fitted_landmarks"]) points.emplace_back(p[0].get<float>(), p[1].get<float>());
    const cv::Rect2f all = cv::boundingRect(points);
    box = cv::Rect2f(all.x + all.width / 4, all.y + all.height / 4, all.width / 2, all.height / 2);
  }
  auto frame_31 = [](const fs::path& path) {  // the last tracked: the input goes on past it
    auto source = open_input(path.string());
    Frame f;
    cv::Mat last;
    for (int i = 0; i < 32 && source->read(f); ++i) last = f.image.clone();
    return last;
  };
  const cv::Mat input = frame_31(video), shaded = frame_31(dir.path() / "shaded.mp4"),
                heat = frame_31(dir.path() / "heatmap.mp4");
  ASSERT_FALSE(input.empty() || shaded.empty() || heat.empty());
  const cv::Rect face(box), corner(input.cols - 40, input.rows - 40, 40, 40);  // the caption is top left
  const auto grey = [](const cv::Mat& image, const cv::Rect& r) {
    const cv::Scalar m = cv::mean(image(r));
    return (m[0] + m[1] + m[2]) / 3;
  };
  EXPECT_GT(grey(shaded, face), 100.0);  // the grey render (albedo 0.75, lit)
  EXPECT_GT(grey(shaded, face), 2.0 * 0.3 * grey(input, face));
  EXPECT_NEAR(grey(shaded, corner), 0.3 * grey(input, corner), 4.0);  // the input dimmed
  EXPECT_NEAR(grey(heat, corner), 0.4 * grey(input, corner), 4.0);
  EXPECT_GT(cv::norm(heat(face), cv::Mat(input(face) * 0.4), cv::NORM_L1) / face.area(),
            50.0);  // coloured (about 250; 5 undrawn)
  // The meshes are the refined finest level (at 400x300 the face is small
  // enough that the hierarchy has a single level: epsilon rule).
  const auto obj = lines(dir.path() / "meshes" / "frame_000031.obj");
  EXPECT_NE(std::find(obj.begin(), obj.end(), "# refined (finest level)"), obj.end());
  EXPECT_GE(std::count_if(obj.begin(), obj.end(), [](const std::string& l) { return l.rfind("v ", 0) == 0; }),
            regions::kFace.num_vertices());
}

// --detail-maps makes an unbroken sequence: a map for every frame, the lost
// one's flat (0 mm everywhere), the refined ones' not.
TEST(TrackJob, ALostFrameGetsAFlatDetailMap) {
  FACECAP_REQUIRE_MODEL(model);
  FACECAP_REQUIRE_DATA(video, "talking_webcam_400x300.mp4");
  TempDir frames;
  write_frames_with_a_blank(video, frames.path(), 14, 10);
  TempDir out;
  TrackOptions o;
  o.capture.quiet = true;
  o.refine = true;
  o.detail_maps = true;
  o.detail_map_size = 64;
  const TrackSummary s = run_track(*model, frames.path().string(), out.path(), o);
  EXPECT_EQ(s.capture.lost, 1);
  EXPECT_EQ(s.detail_maps, 14);
  for (int frame = 0; frame < 14; ++frame) {
    const std::string name = frame_file_name(frame, "png");
    const cv::Mat map = read_png16(out.path() / "detail" / name);
    ASSERT_EQ(map.type(), CV_16UC1) << name;
    const int off_zero = cv::countNonZero(map != 32768);
    if (frame == 10)
      EXPECT_EQ(off_zero, 0) << name;
    else
      EXPECT_GT(off_zero, 64 * 64 / 4) << name;  // the face region's texels
  }
  std::ifstream in(out.path() / "detail" / "detail.json");
  EXPECT_EQ(nlohmann::json::parse(in)["flat_maps"], 1);
}

TEST(TrackJob, BadInputWritesNothing) {
  FACECAP_REQUIRE_MODEL(model);
  TempDir dir;
  const fs::path out = dir.path() / "out";
  EXPECT_THROW(run_track(*model, (dir.path() / "missing.mp4").string(), out, TrackOptions{}), Error);
  EXPECT_FALSE(fs::exists(out / "frames.csv"));
}

}  // namespace facecap
