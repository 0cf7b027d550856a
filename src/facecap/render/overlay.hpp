#pragma once
// Drawings over video frames: landmarks and a mesh wireframe (front-facing
// polygons only), for `--overlay` videos people can check a fit with.
#include <opencv2/core.hpp>

#include "facecap/core/camera.hpp"
#include "facecap/core/mesh.hpp"
#include "facecap/detect/landmarks.hpp"

namespace facecap {

// Small filled dots at the 68 points.
void draw_landmarks(cv::Mat& image, const Landmarks& landmarks, const cv::Scalar& colour, int radius = 2);

// Edges of the polygons whose camera-space normal faces the camera.
void draw_wireframe(cv::Mat& image, const Positions& camera_points, const std::vector<Polygon>& polygons,
                    const PinholeCamera& camera, const cv::Scalar& colour);

// An iris (circle) and the eye's gaze: an arrow from the iris's centre
// (camera frame, cm) along `direction` for `length_cm`.
void draw_gaze(cv::Mat& image, const Vec2d& iris_px, double iris_radius_px, const Vec3d& iris_camera,
               const Vec3d& direction, double length_cm, const PinholeCamera& camera, const cv::Scalar& colour);

// A line of text at the top left, on a dark box so it reads on any frame.
void draw_caption(cv::Mat& image, const std::string& text);

}  // namespace facecap
