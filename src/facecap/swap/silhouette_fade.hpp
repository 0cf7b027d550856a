#pragma once
// The new face where its surface turns away from the view ray.
//
// Near the outer outline, where the frame shows behind the new face, its
// opacity fades: the outline is no UV boundary (the side of the jaw, the
// cheek of a turned head), so the texture's own alpha does not fade it
// there. From the cosine `start` between the normal and the direction to the
// camera (72 degrees) over the next 0.3 (53 degrees); starting at 0.3 rather
// than 0.1 keeps the blend's outer edge on the new face's skin, inside the
// jawline the background warp brings along: seam ratio 2.2 / 2.3 -> 1.1 /
// 0.9 on address_720p_a / _b (eval swap, Biden / Obama, 30 frames). The fade
// holds within `band_px` of the outline and eases off over the next band_px.
//
// Inside, a surface turned away (the underside of the nose, the rims of
// the nostrils, the brow over the eye) has more of the new face behind it.
// Faded there too, it let the target's own nose show through, in a bright
// line around the new one's on every swap of the address clips. It stays
// opaque, and takes the colour of the surface around it that faces the
// camera (soften_turned_away()): rendered as it is, the grazing underside
// of a nose seen from below, which a frontal photo hardly shows, drew a dark
// hard rim against the upper lip.
#include <algorithm>
#include <opencv2/core.hpp>

namespace facecap {

struct SilhouetteFade {
  float start = 0.3f;     // SwapOptions::silhouette_fade_start
  float band_px = 10.0f;  // a tenth of the face's projected width

  // How far the surface turns away, from the cosine between its normal and
  // the direction to the camera: 0 facing the camera (`start` + 0.3 and
  // above), 1 from `start` down, a smooth step between.
  float turned(float facing) const {
    const float f = std::clamp((facing - start) / 0.3f, 0.0f, 1.0f);
    return 1.0f - f * f * (3.0f - 2.0f * f);
  }
  // 1 within band_px of the outline, 0 from twice that inside.
  float near_outline(float outline_px) const { return std::clamp(2.0f - outline_px / band_px, 0.0f, 1.0f); }

  // The factor on the texture's alpha, from turned() and the pixel's
  // distance inside the render's outline (outline_distance()).
  float alpha(float turned, float outline_px) const { return 1.0f - near_outline(outline_px) * turned; }
};

// Where the surface turns away inside the outline (`turned`, CV_32F, as
// SilhouetteFade::turned, and 1 where nothing is drawn; `outline_px` as
// outline_distance()), the render (CV_32FC3) takes the mean colour of the
// surface around it that faces the camera: a normalised blur (two box
// filters, as a Gaussian of band_px / 8), weighed by 1 - turned. (The
// openings inside the outline, where nothing is drawn and the alpha is 0,
// take it too.)
void soften_turned_away(cv::Mat& render, const cv::Mat& turned, const cv::Mat& outline_px, const SilhouetteFade& fade);

}  // namespace facecap
