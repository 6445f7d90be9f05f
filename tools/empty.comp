#version 450
// The least a compute dispatch can do: tools/vulkan_floor.cpp times the driver's own
// start-up with it.
layout(local_size_x = 1) in;
void main() {}
