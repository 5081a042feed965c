#pragma once
// Path data for the reader's and the features' tests of closing: seven relative cubics of a closed
// outline whose coordinates sum back to the start only within round-off (50.1 + … =
// 50.10000000000001). Without the closing command: a test appends "z" (or not).
namespace curvemesh::testing_support {

inline constexpr const char* kClosingWithinRoundOff =
    "M 50.1 0.3 c 0.9017403 10.4244198 -6.222571 24.7737399 -16.120289 31.2732593 "
    "c -9.897718 6.4995194 -28.6473604 10.0435088 -43.266019 7.7238572 "
    "c -14.6186586 -2.3196516 -39.9662093 -12.2496892 -44.4459324 -21.6417669 "
    "c -4.4797231 -9.3920777 10.7398515 -25.3186215 17.567594 -34.7106992 "
    "c 6.8277425 -9.3920777 12.6098751 -19.3221153 23.398861 -21.6417669 "
    "c 10.7889859 -2.3196516 30.8574237 1.2243378 41.3350546 7.7238572 "
    "c 10.4776309 6.4995194 20.6289905 20.8488395 21.5307308 31.2732593 ";

}  // namespace curvemesh::testing_support
