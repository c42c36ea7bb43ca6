namespace rtsim::scenes {}
