#ifndef cycloid_elasticity_digest_h
#define cycloid_elasticity_digest_h

#include <cstddef>

namespace cycloid
{
  namespace elasticity
  {
    /**
     * @brief A 64-bit FNV-1a digest, to recognise a matrix or a constraint
     * structure seen before without keeping a copy of it.
     *
     * Used by SparseCholesky (is this the matrix factorised last?) and by
     * LinearElasticity::structure_digest() (does this constraint set have
     * the lines of the one the pattern was built for?). A digest can
     * collide; both users compare it only with the last one they saw, where
     * a collision would need two different operators with equal digests in
     * consecutive calls.
     */
    class Digest
    {
    public:
      /** Mix in the @p n bytes at @p p. */
      void
      add_bytes(const void *p, const std::size_t n)
      {
        const unsigned char *c = static_cast<const unsigned char *>(p);
        for (std::size_t k = 0; k < n; ++k)
          h = (h ^ c[k]) * prime;
      }

      /** Mix in @p v as one word (faster than its bytes; a different
       * digest from add_bytes() of the same value). */
      void
      add_word(const std::size_t v)
      {
        h = (h ^ v) * prime;
      }

      /** The digest so far. */
      std::size_t
      value() const
      {
        return h;
      }

    private:
      static constexpr std::size_t prime = 1099511628211ull;
      std::size_t                  h     = 1469598103934665603ull;
    };
  } // namespace elasticity
} // namespace cycloid

#endif
