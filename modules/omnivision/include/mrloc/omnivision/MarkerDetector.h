#pragma once
// Robots in a panoramic image (seed 000 Fig. 4): every robot carries the same red band;
// the detector thresholds it (OpenCV), joins the pixels into blobs (connected components,
// across the strip's wrap-around seam and the seams between views) and turns each blob
// into a bearing, the circular mean of its pixels' azimuths. Identity is unknown.
#include <mrloc/omnivision/Panorama.h>
#include <mrpt/img/CImage.h>

#include <vector>

namespace mrloc::omnivision {

struct DetectorOptions {
    int minPixels = 3;      ///< smaller blobs are noise
    int minRed = 100;       ///< red channel at least this
    double redRatio = 2.0;  ///< red at least this times green and blue
};

/** Bearings (robot frame, rad) of the markers in a strip of the given geometry. Throws
 *  mrloc::Error if the image is not a colour strip of that size. */
std::vector<double> detectMarkers(const mrpt::img::CImage& strip, const omnivision::Panorama& p,
                                  const DetectorOptions& o = {});

}  // namespace mrloc::omnivision
