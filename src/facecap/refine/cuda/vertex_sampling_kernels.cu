// Compiled with -fmad=false (CMakeLists): the rasteriser's edge functions and
// the depth test must round as the CPU code does.
#include <cmath>

#include "facecap/refine/cuda/vertex_sampling_kernels.cuh"

namespace facecap::cuda {

namespace {

constexpr int kThreads = 256;
constexpr unsigned kEmpty = 0xffffffffu;
constexpr float kMaxVisibilitySlope = 4.0f;  // rasterizer.cpp's

int blocks_for(int n) { return n > 0 ? (n + kThreads - 1) / kThreads : 1; }

__device__ inline float2 project(const CameraView& c, float x, float y, float z) {
  return {c.focal * x / z + c.cx, c.focal * y / z + c.cy};
}

// rasterizer.cpp's CanonicalEdge: the endpoints in a canonical order, the sign restored.
__device__ inline float edge(float2 a, float2 b, float px, float py) {
  const bool flip = b.x < a.x || (b.x == a.x && b.y < a.y);
  const float2 u = flip ? b : a, v = flip ? a : b;
  const float e = (u.x - px) * (v.y - py) - (u.y - py) * (v.x - px);
  return flip ? -e : e;
}

__global__ void depth_raster_kernel(const float* p, const int* triangles, int num_triangles, CameraView camera,
                                    float near_z, unsigned* depth, int width, int height) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= num_triangles) return;
  const int i0 = triangles[3 * t], i1 = triangles[3 * t + 1], i2 = triangles[3 * t + 2];
  const float ax = p[3 * i0], ay = p[3 * i0 + 1], az = p[3 * i0 + 2];
  const float bx = p[3 * i1], by = p[3 * i1 + 1], bz = p[3 * i1 + 2];
  const float cx = p[3 * i2], cy = p[3 * i2 + 1], cz = p[3 * i2 + 2];
  if (az < near_z || bz < near_z || cz < near_z) return;
  // Back faces: (b - a) x (c - a) . a >= 0, as Eigen evaluates it.
  const float ux = bx - ax, uy = by - ay, uz = bz - az, vx = cx - ax, vy = cy - ay, vz = cz - az;
  const float nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  if (nx * ax + ny * ay + nz * az >= 0.0f) return;
  const float2 p0 = project(camera, ax, ay, az), p1 = project(camera, bx, by, bz), p2 = project(camera, cx, cy, cz);
  const float iz0 = 1.0f / az, iz1 = 1.0f / bz, iz2 = 1.0f / cz;
  const float min_y = fminf(p0.y, fminf(p1.y, p2.y)), max_y = fmaxf(p0.y, fmaxf(p1.y, p2.y));
  if (max_y < 0 || min_y > height - 1) return;
  const float area = (p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x);
  if (fabsf(area) < 1e-8f) return;
  const float inv_area = 1.0f / area;
  const int x0 = max(0, int(ceilf(fminf(p0.x, fminf(p1.x, p2.x)))));
  const int x1 = min(width - 1, int(floorf(fmaxf(p0.x, fmaxf(p1.x, p2.x)))));
  const int y0 = max(0, int(ceilf(min_y)));
  const int y1 = min(height - 1, int(floorf(max_y)));
  for (int y = y0; y <= y1; ++y) {
    const float py = float(y);
    for (int x = x0; x <= x1; ++x) {
      const float px = float(x);
      const float w0 = edge(p1, p2, px, py) * inv_area;
      const float w1 = edge(p2, p0, px, py) * inv_area;
      const float w2 = edge(p0, p1, px, py) * inv_area;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      const float iz = w0 * iz0 + w1 * iz1 + w2 * iz2;
      const float z = 1.0f / iz;
      // Positive floats order as their bits do.
      if (z > 0) atomicMin(depth + size_t(y) * width + x, __float_as_uint(z));
    }
  }
}

__global__ void vertex_samples_kernel(const float* p, const float* n, int num_points, CameraView camera,
                                      const unsigned* depth, ImageView image, float depth_tolerance,
                                      unsigned char* visible, float* colour) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= num_points) return;
  const float px = p[3 * i], py = p[3 * i + 1], pz = p[3 * i + 2];
  const float nx = n[3 * i], ny = n[3 * i + 1], nz = n[3 * i + 2];
  bool seen = false;
  if (pz > 0) {
    // view_facing: -n . p / max(1e-12, |n| |p|).
    const float facing = -(nx * px + ny * py + nz * pz) /
                         fmaxf(1e-12f, sqrtf(nx * nx + ny * ny + nz * nz) * sqrtf(px * px + py * py + pz * pz));
    if (facing > 0.0f) {
      const float2 q = project(camera, px, py, pz);
      const int x = int(lroundf(q.x)), y = int(lroundf(q.y));
      if (x >= 0 && y >= 0 && x < image.width && y < image.height) {
        const float tan_view = sqrtf(fmaxf(0.0f, 1.0f - facing * facing)) / facing;
        const float slope = 0.75f * float(pz / camera.focal_d) * fminf(tan_view, kMaxVisibilitySlope);
        const unsigned bits = depth[size_t(y) * image.width + x];
        const float surface = bits == kEmpty ? INFINITY : __uint_as_float(bits);
        seen = pz <= surface + depth_tolerance + slope;
        if (seen) {
          // sample_bilinear_rgb8 at the projection.
          const float sx = fminf(fmaxf(q.x, 0.0f), float(image.width - 1));
          const float sy = fminf(fmaxf(q.y, 0.0f), float(image.height - 1));
          const int xa = min(int(sx), max(0, image.width - 2)), ya = min(int(sy), max(0, image.height - 2));
          const int xb = min(xa + 1, image.width - 1), yb = min(ya + 1, image.height - 1);
          const float fx = sx - xa, fy = sy - ya;
          const unsigned char* r0 = image.bgr + size_t(ya) * image.pitch;
          const unsigned char* r1 = image.bgr + size_t(yb) * image.pitch;
          for (int k = 0; k < 3; ++k) {
            const float v = (r0[3 * xa + k] * (1 - fx) + r0[3 * xb + k] * fx) * (1 - fy) +
                            (r1[3 * xa + k] * (1 - fx) + r1[3 * xb + k] * fx) * fy;
            colour[3 * i + 2 - k] = v / 255.0f;
          }
        }
      }
    }
  }
  visible[i] = seen ? 1 : 0;
  if (!seen)
    for (int k = 0; k < 3; ++k) colour[3 * i + k] = 0.0f;
}

}  // namespace

void launch_depth_raster(const float* points, int, const int* triangles, int num_triangles, const CameraView& camera,
                         float near_z, unsigned* depth, int width, int height, cudaStream_t s) {
  cudaMemsetAsync(depth, 0xff, size_t(width) * height * sizeof(unsigned), s);
  if (num_triangles > 0)
    depth_raster_kernel<<<blocks_for(num_triangles), kThreads, 0, s>>>(points, triangles, num_triangles, camera, near_z,
                                                                       depth, width, height);
}

void launch_vertex_samples(const float* points, const float* normals, int num_points, const CameraView& camera,
                           const unsigned* depth, const ImageView& image, float depth_tolerance, unsigned char* visible,
                           float* colour, cudaStream_t s) {
  if (num_points > 0)
    vertex_samples_kernel<<<blocks_for(num_points), kThreads, 0, s>>>(points, normals, num_points, camera, depth, image,
                                                                      depth_tolerance, visible, colour);
}

}  // namespace facecap::cuda
