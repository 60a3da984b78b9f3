#ifndef cycloid_profile_dxf_writer_h
#define cycloid_profile_dxf_writer_h

#include <cycloid/profile/outline.h>

#include <string>

namespace cycloid
{
  namespace profile
  {
    /**
     * Write @p outline to @p filename as an ASCII DXF (AutoCAD R12,
     * `$ACADVER` AC1009, `$INSUNITS` 4 = mm): the profile as one closed
     * `POLYLINE` (flag 1) of `VERTEX` entities ended by `SEQEND` on layer
     * `PROFILE`, each hole as a `CIRCLE` on layer `HOLES`; coordinates with
     * 15 significant digits. R12 is written because it needs no object
     * handles, so a hand-written file is complete and every reader takes
     * it. Throws dealii::ExcMessage if the file cannot be written.
     */
    void
    write_dxf(const DiscOutline &outline, const std::string &filename);
  } // namespace profile
} // namespace cycloid

#endif
