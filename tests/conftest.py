"""Shared test fixtures: where the repository, its examples and the shared corpus are; and the markers
(registered in pyproject.toml) each test gets here, by module, by name, or by the fixtures it uses:

* ``ros``: needs ROS 1 or ROS 2 tools: rosmaster, Debian's rospy, catkin, roslaunch, colcon, a peer's rclpy;
* ``browser``: needs chromium (every test using the ``chromium`` fixture);
* ``slow``: a pure test of a second or more, measured on the 2-core development machine while other jobs loaded
  it (a simulation in a child process, libsdformat, a package build, a process killed mid-write).

The fast loop, under a minute on that machine: ``python -m pytest -m "not ros and not browser and not slow"``.
"""

from __future__ import annotations

import fnmatch
import signal
from pathlib import Path

import pytest

# A suite started in the background (`nohup pytest … &` from a script) has SIGINT ignored, and every command a test
# starts would inherit that: the tests that stop `worldgen sim` or `run` as Ctrl-C does would wait on it, and leave
# it running. Here SIGINT is Python's own again, so that children start with it at its default.
if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)

from browserpage import chromium  # noqa: F401  (one headless browser for every test module)

REPO = Path(__file__).resolve().parent.parent
EXAMPLES = REPO / "examples"
SHARED = REPO.parent / "shared"
CORPUS = SHARED / "corpus"


@pytest.fixture(scope="session")
def corpus() -> Path:
    """``../shared/corpus`` (real worlds saved with Gazebo); tests using it skip when it is absent."""
    if not CORPUS.is_dir():
        pytest.skip(f"the shared corpus is not beside this checkout ({CORPUS} is missing)")
    return CORPUS


def CliRunner():   # noqa: N802  (stands in for click.testing.CliRunner in every test)
    """click's test runner with stderr apart from stdout, and ``output`` holding both, as click 8.2+ gives
    them; click 8.1 (the last for Python 3.8) mixes them unless asked, and then ``output`` is stdout alone."""
    import inspect

    from click.testing import CliRunner as Runner

    if "mix_stderr" not in inspect.signature(Runner.__init__).parameters:
        return Runner()

    class _Result:
        def __init__(self, result):
            self._result = result

        def __getattr__(self, name):
            return getattr(self._result, name)

        @property
        def output(self) -> str:
            return self._result.stdout + self._result.stderr

    class _Runner(Runner):
        def __init__(self, **kwargs):
            super().__init__(mix_stderr=False, **kwargs)

        def invoke(self, *args, **kwargs):
            return _Result(super().invoke(*args, **kwargs))

    return _Runner()


# ------------------------------------------------------------------------------------------------------ markers

# Modules whose every test needs ROS: `worldgen sim`/`run` with a real master and rospy nodes, the ROS 1 tools,
# students' rclpy nodes and the DDS plumbing against a peer's rclpy.
ROS_MODULES = ("test_bridge_*.py", "test_ros_tools.py", "test_ros2_live.py", "test_ros2_dds.py")
PURE_MODULES = ("test_bridge_rubrics.py",)   # rubrics on made-up traces: no ROS
# Tests that need ROS in modules of mostly pure ones, and why.
ROS_TESTS = {
    "test_course.py": ("test_front_distance_ignores_inf_zero_and_nan", "test_the_node_runs_drives_law",
                       "test_the_law_never_reverses_and_holds_through_noise"),   # import the rospy node
    "test_launch_params.py": ("test_roslaunchs_own_loader_finds_the_same_parameters",),   # roslaunch
    "test_readme.py": ("test_every_readme_command_runs_as_written",),                     # catkin_make
    "test_ros2_packages.py": ("test_colcon_builds_the_workspace",),                      # colcon
    "test_scaffold.py": ("test_same_meaning_as_catkin_create_pkg", "test_metapackage"),  # catkin_create_pkg
}
ROS_FIXTURES = ("tag", "ros2_tag", "rclpy_python")   # a run's processes with a real master; a peer's rclpy
BROWSER_FIXTURES = ("chromium",)
# Pure tests of a second or more (see the module docstring), by module.
SLOW_TESTS = {
    "test_absurd_coordinates.py": ("test_a_shape_beyond_reach_is_a_finding_not_a_crash",),
    "test_bad_input.py": ("test_build_exits_2_and_writes_nothing", "test_message_names_file_line_and_fix"),
    "test_bounded_meshes.py": ("test_a_mesh_over_the_budget_is_skipped_before_it_is_parsed",
                               "test_a_soup_within_the_budget_gets_a_verdict",
                               "test_a_world_past_its_triangle_budget_skips_the_meshes_past_it"),
    "test_drive.py": ("test_drive_bad_input_exits_2", "test_drive_from_a_spec",
                      "test_drive_reports_a_collision_with_exit_1", "test_drive_spin",
                      "test_drive_stop_at_wall_with_plot_and_csv", "test_run_isolated_reports_crashes_and_timeouts"),
    "test_drive_scans.py": ("test_a_faster_control_loop_records_at_most_five_scans_a_second",
                            "test_recording_changes_nothing_else", "test_spin_records_scans_turning_with_the_robot",
                            "test_stop_at_wall_records_the_scans_the_controller_saw",
                            "test_stop_at_wall_series_has_the_path"),
    "test_examples.py": ("test_example_builds_previews_and_encloses_as_it_says",),
    "test_generate.py": ("test_a_seed_gives_the_same_bytes_in_fresh_processes",
                         "test_a_seed_gives_the_same_bytes_on_every_python_here",
                         "test_arena_is_one_closed_room_that_is_not_convex",
                         "test_clutter_every_gap_is_closed_or_passable", "test_libsdformat_accepts_the_built_worlds",
                         "test_maze_every_cell_is_reachable_and_room_to_turn",
                         "test_preview_of_a_folder_draws_every_world_to_one_scale",
                         "test_rooms_every_room_is_reachable_through_its_doors",
                         "test_track_bends_no_tighter_than_the_limit"),
    "test_grading.py": ("test_a_bad_shard_is_bad_usage",
                        "test_drive_in_a_folder_drives_each_launch_files_world_from_its_spawn",
                        "test_the_folder_is_graded_per_package_with_each_launch_files_spawn",
                        "test_the_junit_report_gives_each_submission_its_verdict",
                        "test_the_readme_grading_command_runs_as_written",
                        "test_the_readme_text_report_is_what_validate_prints"),
    "test_hostile_cli.py": ("test_build", "test_drive_on_junk_worlds", "test_launch", "test_new", "test_preview",
                            "test_scaffold", "test_validate"),
    "test_hostile_inputs.py": ("test_any_launch_file_is_judged_or_refused", "test_any_spec_builds_or_is_refused",
                               "test_any_world_is_judged_or_refused"),
    "test_launch.py": ("test_every_default_spawn_in_the_corpus_is_free",),
    "test_launch_params.py": ("test_a_hostile_rosparam_document_is_refused_quickly",),
    "test_launch_py.py": ("test_any_launch_file_is_read_or_refused_with_a_line",),
    "test_limits.py": ("test_a_triangle_soup_is_taken_as_its_hull_with_a_warning", "test_bad_yaml_is_one_line",
                       "test_floor_markings_are_bounded", "test_include_fanout_and_depth_are_refused",
                       "test_many_boxes_give_the_same_enclosure_as_the_exact_path",
                       "test_ten_thousand_boxes_are_checked_in_seconds"),
    "test_markings.py": ("test_every_list_of_markings_is_bounded",
                         "test_markings_are_byte_identical_and_pass_libsdformat",
                         "test_the_line_track_template_validates_and_its_tape_changes_no_other_check",
                         "test_the_preview_draws_the_tape_in_its_colour"),
    "test_occupancy.py": ("test_example_validates",),
    "test_output_suffixes.py": ("test_the_right_suffix_writes_what_it_says",),
    "test_preview.py": ("test_grid_posts_are_drawn_as_walls", "test_lidar_rays_end_on_the_walls",
                        "test_preview_command_writes_the_png", "test_preview_spawn_and_robot_options",
                        "test_spec_picture_marks_doors_windows_obstacles_and_spawn"),
    "test_reader.py": ("test_a_400_room_building_reads",),
    "test_readme.py": ("test_the_first_command_installs_and_checks_on_a_pep668_system",),
    "test_robot_cache.py": ("test_a_kept_description_is_the_processed_one_and_the_next_process_skips_xacro",),
    "test_ros2_msgs.py": ("test_bytes_equal_rosbags_and_read_back_equal",
                          "test_nothing_outside_ros2_imports_cyclonedds_at_import_time",
                          "test_random_samples_equal_rosbags", "test_stamps_floor_and_order"),
    "test_ros2_validate.py": ("test_a_colcon_workspace_reports_each_ament_package_and_launch_file",
                              "test_a_humble_package_is_checked_from_its_spawn_entity_pose",
                              "test_a_world_given_with_a_python_launch_file_takes_its_spawn",
                              "test_humble_and_jazzy_launch_files_pass_in_the_simulator",
                              "test_robotis_jazzy_world_through_a_package_of_that_shape"),
    "test_ros2_world.py": ("test_build_writes_it_and_validate_gives_the_classic_verdict",
                           "test_libsdformat_accepts_the_gz_world"),
    "test_run_leftovers.py": ("test_a_supervisor_ends_a_daemon_ignoring_sigterm_and_names_its_owner",
                              "test_a_supervisor_killed_with_sigkill_leaves_nothing"),
    "test_runtime.py": ("test_doctor_json_and_exit_codes", "test_doctor_prints_the_table_and_one_apt_line",
                        "test_every_debian_name_in_the_table_exists",
                        "test_pictures_draw_quietly_beside_debians_matplotlib"),
    "test_runtime_ros2.py": ("test_doctor_and_run_name_ros2_packages_and_start_nothing",),
    "test_safe_writes.py": ("test_build_model_dir_force_killed", "test_build_package_killed",
                            "test_course_force_killed", "test_scaffold_force_killed",
                            "test_two_builds_without_force_one_wins", "test_two_scaffolds_without_force_one_wins"),
    "test_sdfcheck.py": ("test_every_version_passes_libsdformat", "test_examples_build_into_valid_worlds",
                         "test_stand_ins_for_gazebo_stock_models"),
    "test_self_check.py": ("test_everything_worldgen_writes_validates_without_a_word",
                           "test_worldgen_specs_and_worlds_pass_the_simulator_too"),
    "test_sim_forks.py": ("test_a_crash_in_the_forked_simulation_is_a_finding",
                          "test_a_crash_or_a_hang_ends_its_run_alone_and_nothing_is_left",
                          "test_an_early_run_that_read_another_world_is_simulated_again_on_the_checked_scene"),
    "test_validate.py": ("test_class_room_with_the_course_launch_file",
                         "test_exit_code_2_for_bad_input_with_one_line", "test_json_shape",
                         "test_libsdformat_checks_included_models_from_the_model_path",
                         "test_lidar_no_hit_reads_inf_or_zero_in_a_big_room", "test_our_examples_pass",
                         "test_our_examples_pass_libsdformat",
                         "test_progress_in_a_log_is_one_line_per_file_on_stderr",
                         "test_results_keep_input_order_with_two_workers",
                         "test_stop_at_wall_turns_to_face_the_nearest_wall"),
    "test_validate_corpus.py": ("test_corpus_details_at_origin", "test_corpus_file_outcome",
                                "test_empty_world_in_the_simulator",
                                "test_every_corpus_file_has_a_stated_expectation",
                                "test_robotis_jazzy_worlds_name_their_fuel_includes_without_fetching",
                                "test_robotis_worlds_pass_with_their_launch_spawn",
                                "test_without_a_spawn_the_moved_class_room_is_checked_from_its_middle"),
    "test_view.py": ("test_a_run_is_thinned_to_what_the_eye_needs", "test_drive_html_replays_the_stop",
                     "test_thinning_keeps_a_sensors_own_rate_through_its_jitter"),
    "test_wheel.py": ("test_course_and_robot_work_from_the_wheel", "test_three_js_modules_load_from_the_wheel",
                      "test_wheel_holds_templates_and_robot_descriptions",
                      "test_wheel_holds_three_js_and_its_license_not_the_build_hook"),
}


def markers_of(module: str, name: str, fixtures=()) -> set[str]:
    """The markers a test ``name`` of ``module`` (a file name) gets, using ``fixtures``."""
    found = set()
    if (any(fnmatch.fnmatch(module, p) for p in ROS_MODULES) and module not in PURE_MODULES) or \
            name in ROS_TESTS.get(module, ()) or any(f in ROS_FIXTURES for f in fixtures):
        found.add("ros")
    if any(f in BROWSER_FIXTURES for f in fixtures):
        found.add("browser")
    if name in SLOW_TESTS.get(module, ()):
        found.add("slow")
    return found


# The longest modules, longest first (by their seconds with ``--durations=0`` under ``-n 3``), so that the README's
# parallel run (``-n 3 --dist loadfile``: a module stays on one worker, its fixtures made once) starts them first
# and no long module starts last, alone. The rest follow in their usual order.
LONGEST_FIRST = ("test_readme.py",             # every README command; the first one's venv install
                 "test_ros2_live.py",          # students' rclpy nodes against the DDS transport
                 "test_bridge_line.py",        # camera line following, 80 simulated seconds a lap
                 "test_safe_writes.py",        # writers killed mid-write, again and again
                 "test_bridge_worlds.py",      # 24 runs across generated worlds
                 "test_bridge_readme.py", "test_bridge_run.py", "test_bridge_camera.py", "test_bridge_tasks.py",
                 "test_run_leftovers.py", "test_bridge_sim.py", "test_bridge_params.py", "test_bridge_robots.py",
                 "test_validate.py", "test_bridge_runtime.py", "test_ros_tools.py", "test_ros2_packages.py",
                 "test_limits.py", "test_generate.py", "test_view_browser.py", "test_bridge_gazebo.py",
                 "test_ros2_dds.py", "test_absurd_coordinates.py", "test_bridge_view.py", "test_validate_corpus.py",
                 "test_grading.py", "test_ros2_world.py", "test_bridge_scans.py", "test_bounded_meshes.py",
                 "test_ros2_msgs.py", "test_bridge_clock.py", "test_drive.py", "test_layout.py", "test_ros1_env.py",
                 "test_wheel.py")


def pytest_configure(config):
    """Modules go to the workers in :data:`LONGEST_FIRST`'s order: xdist 3.7+ would sort them by their number of
    tests instead (3.6, the last for Python 3.8, keeps the order and has no option to ask it to)."""
    if hasattr(config.option, "loadscopereorder"):
        config.option.loadscopereorder = False


def _start_order(item) -> int:
    name = item.path.name
    return LONGEST_FIRST.index(name) if name in LONGEST_FIRST else len(LONGEST_FIRST)


@pytest.hookimpl(tryfirst=True)   # before -m selects by them
def pytest_collection_modifyitems(config, items):
    for item in items:
        name = getattr(item, "originalname", None) or item.name.split("[")[0]
        for marker in sorted(markers_of(item.path.name, name, getattr(item, "fixturenames", ()))):
            item.add_marker(getattr(pytest.mark, marker))
    items.sort(key=_start_order)   # stable: each module's own order is kept
