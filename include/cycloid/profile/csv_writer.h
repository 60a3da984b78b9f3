#ifndef cycloid_profile_csv_writer_h
#define cycloid_profile_csv_writer_h

#include <cycloid/profile/outline.h>

#include <string>

namespace cycloid
{
  namespace profile
  {
    /**
     * Write the polyline of @p outline to @p filename as CSV: the header
     * `x_mm,y_mm`, then one row per vertex, counter-clockwise, with 15
     * significant digits; the last row repeats the first so that the file
     * is closed on its own. The holes are not in this file (see the DXF
     * and STEP files). Throws dealii::ExcMessage if the file cannot be
     * written.
     */
    void
    write_csv(const DiscOutline &outline, const std::string &filename);
  } // namespace profile
} // namespace cycloid

#endif
