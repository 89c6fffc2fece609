// The post-processor's table angles against LinuxCNC's own kinematics: the xyzac-trt-kins module
// (Debian package linuxcnc-uspace) is loaded, with the few HAL and RTAPI functions it calls
// stood in for here (its pins, the pivot and tool offsets, all 0), and its inverse kinematics
// turns the angles Gcode.hpp chooses into joints. A layer's tool axis must then run along the
// machine's +Z, where the nozzle points from. An executable of its own: the module resolves the
// stand-ins against it (ENABLE_EXPORTS).
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "mas/Angles.hpp"
#include "mas/Gcode.hpp"

#ifndef MAS_LINUXCNC_KINS
#define MAS_LINUXCNC_KINS "/usr/lib/linuxcnc/modules/xyzac-trt-kins.so"
#endif

// What the module calls of HAL and RTAPI. Pins are zeroed memory: rot points and offsets are 0,
// and the kinematics type pin 0 selects the tool-centre-point kinematics (trtfuncs.c).
extern "C" {
int hal_init(const char*) { return 1; }
void* hal_malloc(long size) { return std::calloc(1, size < 8 ? 8 : static_cast<size_t>(size)); }
int hal_pin_float_newf(int, double** pin, int, const char*, ...) {
    *pin = static_cast<double*>(std::calloc(1, sizeof(double)));
    return 0;
}
int hal_pin_bit_new(const char*, int, void** pin, int) {
    *pin = std::calloc(1, 8);
    return 0;
}
int hal_pin_s32_new(const char*, int, int** pin, int) {
    *pin = static_cast<int*>(std::calloc(1, 8));
    return 0;
}
int hal_ready(int) { return 0; }
int hal_exit(int) { return 0; }
void rtapi_print(const char*, ...) {}
void rtapi_print_msg(int, const char*, ...) {}
}

using mas::kPi;

namespace {

// LinuxCNC's EmcPose: tran (x, y, z), a, b, c, u, v, w.
struct EmcPose {
    double x, y, z, a, b, c, u, v, w;
};
using Inverse = int (*)(const EmcPose*, double*, const unsigned long*, unsigned long*);

TEST(LinuxCncKinematics, TheTableAnglesTurnEveryLayersAxisUpToTheNozzle) {
    void* module = dlopen(MAS_LINUXCNC_KINS, RTLD_NOW | RTLD_GLOBAL);
    ASSERT_NE(module, nullptr) << "cannot load LinuxCNC's kinematics (package linuxcnc-uspace, "
                                  "installed by tools/setup.sh): "
                               << dlerror();
    auto main = reinterpret_cast<int (*)()>(dlsym(module, "rtapi_app_main"));
    auto inverse = reinterpret_cast<Inverse>(dlsym(module, "kinematicsInverse"));
    ASSERT_NE(main, nullptr);
    ASSERT_NE(inverse, nullptr);
    ASSERT_EQ(main(), 0);

    const double degree = kPi / 180.0;
    std::mt19937 random(11);
    std::uniform_real_distribution<double> tilt(0.0, 100.0), turn(-180.0, 180.0);
    const mas::MachineParams machine;  // A -100 to 50
    double previous_a = 0.0, previous_c = 0.0;
    for (int i = 0; i < 1000; ++i) {
        const double t = tilt(random) * degree, c = turn(random) * degree;
        const Eigen::Vector3d n(std::sin(t) * std::cos(c), std::sin(t) * std::sin(c), std::cos(t));
        mas::TableAngles angles;
        ASSERT_TRUE(mas::table_angles(n, machine, previous_a, previous_c, angles));
        // The joints of a tip at p and at p + n, the table at the same angles.
        const Eigen::Vector3d p(3.0 * i - 40.0, -7.0, 11.0 + i % 13);
        const EmcPose at{p.x(), p.y(), p.z(), angles.a_deg, 0, angles.c_deg, 0, 0, 0};
        const EmcPose along{
            p.x() + n.x(), p.y() + n.y(), p.z() + n.z(), angles.a_deg, 0, angles.c_deg, 0, 0, 0};
        double j0[9] = {0}, j1[9] = {0};
        unsigned long inverse_flags = 0, forward_flags = 0;
        ASSERT_EQ(inverse(&at, j0, &inverse_flags, &forward_flags), 0);
        ASSERT_EQ(inverse(&along, j1, &inverse_flags, &forward_flags), 0);
        const Eigen::Vector3d machine_axis(j1[0] - j0[0], j1[1] - j0[1], j1[2] - j0[2]);
        EXPECT_LE((machine_axis - Eigen::Vector3d::UnitZ()).norm(), 1e-12)
            << "axis " << n.transpose() << " at A " << angles.a_deg << " C " << angles.c_deg;
        EXPECT_EQ(j0[3], angles.a_deg);  // the rotary joints are the words
        EXPECT_EQ(j0[4], angles.c_deg);
        previous_a = angles.a_deg;
        previous_c = angles.c_deg;
    }
}

}  // namespace
