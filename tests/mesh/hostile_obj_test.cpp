// Malformed OBJ: each is refused with BadInput and a message naming the line or element, in
// process; through limn-classify in hostile_obj_cli_test.cpp.
#include "base/error.h"
#include "hostile_obj_cases.h"
#include "mesh/obj.h"

#include <gtest/gtest.h>

using namespace limn;
using namespace limn::test::hostile_obj;

namespace {

TEST(HostileObj, RejectedInProcess) {
    for (const auto& c : kCases) {
        SCOPED_TRACE(c.name);
        Warnings w;
        try {
            readObj({reinterpret_cast<const uint8_t*>(c.obj.data()), c.obj.size()}, w);
            ADD_FAILURE() << "accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            std::string text = (e.where().empty() ? "" : e.where() + ": ") + e.what();
            EXPECT_NE(text.find(c.message), std::string::npos) << text;
        }
    }
}

} // namespace
