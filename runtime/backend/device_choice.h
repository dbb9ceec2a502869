// Choosing devices from a backend's list by --device: the rules every backend's list shares.
#pragma once

#include <string>
#include <vector>

#include "runtime/backend/device_info.h"

namespace cohort {

// "" picks the device $COHORT_DEVICE names (any spec below; how the tests and scripts/test-vendors
// choose a runtime), else the first GPU, else the first CPU device; otherwise an index into `devices`
// or a case-insensitive substring of the device or platform name. Throws InputError when nothing
// matches. `devices` must not be empty.
DeviceInfo select_device(const std::vector<DeviceInfo>& devices, const std::string& spec);

// Several devices: "all" (every device), "all:NAME" (every device whose device or platform name
// contains NAME), "rank:NAME" (of the devices matching NAME, the one at this process's rank among
// the MPI ranks of its machine, modulo their count: one GPU per rank), or a comma list of single
// specs as select_device takes them, each naming a different device (a repeated name picks the
// next device that matches). One spec without a comma is select_device's choice. Throws
// InputError when an item matches nothing new.
std::vector<DeviceInfo> select_devices(const std::vector<DeviceInfo>& devices, const std::string& spec,
                                       int local_rank = 0);

}  // namespace cohort
