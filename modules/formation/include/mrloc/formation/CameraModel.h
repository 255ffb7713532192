#pragma once
// A camera as real as the lab's (seed 003 sec. 4: low-cost monocular cameras): the renderer's
// ideal pinhole picture is distorted by the lens (OpenCV's Brown-Conrady model), blurred,
// exposed and given sensor noise before AprilTag 3 searches it; the robot then undistorts
// the tags' corners with the calibration it believes (which may be off by
// `calibrationError`), as it would with OpenCV. Tags then fail at distance or angle because
// the real detector fails on the degraded picture, not by a drawn failure rate.
#include <mrloc/formation/Markers.h>
#include <mrpt/img/CImage.h>
#include <mrpt/img/TCamera.h>
#include <mrpt/random/RandomGenerators.h>

#include <memory>
#include <vector>

namespace mrloc::formation {

struct CameraModelOptions {
    double k1 = 0, k2 = 0;        ///< radial distortion (OpenCV's k1, k2)
    double p1 = 0, p2 = 0;        ///< tangential distortion
    double calibrationError = 0;  ///< the robot's k1, k2, p1, p2: the true ones x (1 + this)
    double blur = 0;              ///< px, Gaussian blur's sd (defocus and residual motion)
    double noise = 0;             ///< grey levels (0-255), the sensor noise's sd per pixel
    double exposure = 1;          ///< gain on the picture's levels (< 1 darker, > 1 brighter)
    /** Nothing to do: the ideal picture is the camera's. */
    bool ideal() const {
        return k1 == 0 && k2 == 0 && p1 == 0 && p2 == 0 && blur == 0 && noise == 0 && exposure == 1;
    }
};

class CameraModel {
 public:
    /** Throws mrloc::Error naming the option for values out of their bounds. */
    CameraModel(const mrpt::img::TCamera& intrinsics, const CameraModelOptions& options);
    ~CameraModel();
    CameraModel(CameraModel&&) noexcept;
    CameraModel& operator=(CameraModel&&) noexcept;

    /** The ideal pinhole picture to render for this camera: the camera's own, or, with lens
     *  distortion, a larger one of the same focal length that holds every ray the lens sees
     *  (a barrel lens sees beyond the pinhole picture). */
    const mrpt::img::TCamera& renderIntrinsics() const;
    /** The camera's own intrinsics: the frame the undistorted tags are in. */
    const mrpt::img::TCamera& intrinsics() const;
    /** The tags the robot finds in a rendered picture (of renderIntrinsics()): the picture degraded
     * as the camera takes it (noise drawn from `rng`), searched by AprilTag 3 at full resolution,
     * each tag's corners undistorted with the robot's calibration. */
    std::vector<MarkerSighting> see(const mrpt::img::CImage& rendered,
                                    mrpt::random::CRandomGenerator& rng) const;
    /** The rendered picture as the camera takes it (grey levels). */
    mrpt::img::CImage degrade(const mrpt::img::CImage& rendered,
                              mrpt::random::CRandomGenerator& rng) const;
    const CameraModelOptions& options() const;

 private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace mrloc::formation
