# The camera's motion from the scene (cv::rgbd::RgbdICPOdometry), an estimate independent of the tags.
find_package(OpenCV REQUIRED COMPONENTS rgbd)
target_link_libraries(notebook_real_cube PRIVATE opencv_rgbd)
