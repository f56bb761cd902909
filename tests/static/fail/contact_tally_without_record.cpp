// SPDX-License-Identifier: MIT
// Must not compile: a contact law whose `tally` has no record(): without the check the counts
// would be ignored in silence; contact::check names what the tally needs.
// GIMLET_FAILTEST_EXPECT: a `tally` needs
#include <gimlet/contact/check.hpp>

#include <cstdint>

struct counting {
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<>;
    template <gimlet::Space S>
    bool in_contact(const gimlet::contact::pair_view<S>&) const {
        return true;
    }
    struct tally {
        std::uint64_t pairs = 0;
        tally& operator+=(const tally& o) {
            pairs += o.pairs;
            return *this;
        }
    };
    template <gimlet::Space S>
    void count(tally& t, const gimlet::contact::pair_view<S>&, const gimlet::contact::pair_outcome<S>&) const {
        ++t.pairs;
    }
#ifdef GIMLET_FAILTEST_OK
    void record(const tally& t) { total += t; }
#endif
    tally total;
};

static_assert(gimlet::contact::check<counting>());

int main() { return 0; }
