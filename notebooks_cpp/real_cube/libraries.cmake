# The camera's motion from the scene (cv::rgbd::RgbdICPOdometry), an estimate independent of the tags;
# solvePnP (calib3d) for the board pose refits from the raw tag corners.
find_package(OpenCV REQUIRED COMPONENTS rgbd calib3d)
target_link_libraries(notebook_real_cube PRIVATE opencv_rgbd opencv_calib3d)
