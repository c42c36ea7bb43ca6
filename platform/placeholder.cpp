namespace rtsim::platform {}
