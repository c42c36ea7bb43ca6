namespace rtsim::app {}
