sphere { 0, 1 pigment { bozo } }
