#pragma once
// Robots in a panoramic image (seed 000 Fig. 4): every robot carries the same red band;
// the detector thresholds it (OpenCV), joins the pixels into blobs (connected components,
// across the strip's wrap-around seam and the seams between views) and turns each blob
// into a bearing, the middle of the azimuths its columns span. Identity is unknown.
//
// In a crowd, markers overlap and merge into one blob (beyond the paper: seed 000 has five
// robots). Given the band's size, the detector splits a blob where its height steps (a
// marker's height in the image is inversely proportional to its depth) and keeps only the
// pieces that are in front and as wide as their height says a whole band is; a marker
// partly hidden behind another is dropped rather than given a biased bearing.
#include <mrloc/omnivision/Panorama.h>
#include <mrpt/img/CImage.h>

#include <vector>

namespace mrloc::omnivision {

struct DetectorOptions {
    int minPixels = 3;      ///< smaller blobs are noise
    int minRed = 100;       ///< red channel at least this
    double redRatio = 2.0;  ///< red at least this times green and blue
    /** The band's radius and height (m). Both > 0: overlapping markers are split and the
     *  pieces checked against the band's size; 0: every blob is one marker. */
    double markerRadius = 0, markerHeight = 0;
    /** px: a blob is cut where its column height changes by this much. The band straddles
     *  the strip's middle row, so a column's red rows come in pairs: 2 is one quantum. */
    int heightStep = 2;
    /** px: a piece's height is its band's within this (the rows' quantisation). */
    double heightSlack = 1;
};

/** Bearings (robot frame, rad) of the markers in a strip of the given geometry. Throws
 *  mrloc::Error if the image is not a colour strip of that size. */
std::vector<double> detectMarkers(const mrpt::img::CImage& strip, const omnivision::Panorama& p,
                                  const DetectorOptions& o = {});

}  // namespace mrloc::omnivision
