"""A Sim run with one camera, recorded and exported to a LeRobot v3 dataset in one command
(`comply export --lerobot`), read back by two Parquet readers independent of comply's writer
(hyparquet and DuckDB, Node: tests/export/read_parquet*.mjs) and by ffprobe and ffmpeg:

- the data table has a row per frame, timestamps exactly i / fps (float32), and each row's
  observation, action, stiffness, damping and task frame are the cycle record's in force at that
  time (the last stamped at or before it), as comply.read_recording reads the recording;
- the camera's video has one frame per row (ffprobe), and frame i shows the image the Sim
  observed last at or before row i's time (the decoded frame is nearest to that image among the
  episode's images);
- the episodes' table places each episode's rows and video frames, and meta/stats.json holds
  numpy's statistics of the rows and of the decoded frames;
- Foxglove's deserializer decodes the recording's camera channel (sensor_msgs/CompressedImage);
- a reset's frames are the first reset's, a TCP camera's frames move with the arm, and a camera
  that cannot be rendered is refused naming it.

    camera_dataset_test.py COMPLY_CLI SOURCE_DIR
"""

import json
import os
import subprocess
import sys
import tempfile

import numpy as np

import comply

FPS = 30            # the dataset's rate; the policy steps at 20 Hz, so frames hold images
STEPS = 12          # policy steps per episode (0.6 s)
STEPS_PER_ACTION = 50
EPISODES = 2
WIDTH, HEIGHT = 64, 48
CAMERA = {"front": {"width": WIDTH, "height": HEIGHT, "lookat": [0.4, 0.0, 0.4],
                    "distance": 1.0, "azimuth": 160.0, "elevation": -20.0}}


def run_sim(source, recording):
    """EPISODES episodes moving the TCP 8 cm at a new stiffness each step; the observed images
    with their times, per episode."""
    sim = comply.Sim(f"{source}/config/sim/cartesian_impedance.yaml", robot="fr3",
                     steps_per_action=STEPS_PER_ACTION, record=recording, cameras=CAMERA)
    episodes = []
    for episode in range(EPISODES):
        obs = sim.reset()
        assert obs["images"]["front"].shape == (HEIGHT, WIDTH, 3), obs["images"]["front"].shape
        assert obs["images"]["front"].dtype == np.uint8
        start, orientation = obs["tcp_position"].copy(), obs["tcp_orientation"]
        images = [(obs["time"], obs["images"]["front"])]
        for step in range(STEPS):
            target = start + [0.0, (0.08 if episode == 0 else -0.08) * (step + 1) / STEPS, 0.0]
            stiffness = 1500.0 + 100.0 * step
            obs, _, terminated, _, info = sim.step({"position": target,
                                                    "orientation": orientation,
                                                    "stiffness_translational": stiffness})
            assert info["accepted"] and not terminated, info
            images.append((obs["time"], obs["images"]["front"]))
        episodes.append(images)
    # The arm moved: the images are not all the same.
    assert not np.array_equal(episodes[0][0][1], episodes[0][-1][1])
    sim.close()
    return episodes


def check_cameras(source):
    """Frames of the state the observation reports: a reset (which keeps the GL contexts, on a
    new plant) shows what the first one did, a TCP camera moves with the arm, and a camera that
    cannot be rendered is refused naming the camera and what is wrong."""
    config = f"{source}/config/sim/cartesian_impedance.yaml"
    sim = comply.Sim(config, robot="fr3", cameras={
        "front": {"width": 32, "height": 24},
        "wrist": {"mount": "tcp", "width": 32, "height": 24, "fovy": 70,
                  "position": [0.0, 0.05, -0.08], "orientation": [0, 0, 0, 1]}})
    first = sim.reset()
    start = first["tcp_position"].copy()
    moved = first
    for _ in range(6):
        moved, *_ = sim.step({"position": start + [0.0, 0.0, -0.1],
                              "orientation": first["tcp_orientation"]})
    assert not np.array_equal(moved["images"]["wrist"], first["images"]["wrist"])
    again = sim.reset()
    for name in ("front", "wrist"):
        np.testing.assert_array_equal(again["images"][name], first["images"][name])
    for cameras, words in [({"a": {"width": 31}}, "camera 'a': 31 x 96 pixels"),
                           ({"a": {"zoom": 2}}, "camera 'a': unknown key 'zoom'"),
                           ({"a": {"mount": "tcp", "lookat": [0, 0, 0]}}, "lookat is not a key"),
                           ({"a": {"mount": "hand"}}, "mount must be 'scene' or 'tcp'"),
                           ({"a": {"fovy": 0}}, "fovy")]:
        try:
            comply.Sim(config, robot="fr3", cameras=cameras)
            raise AssertionError(f"{cameras} was accepted")
        except ValueError as error:
            assert words in str(error), (words, str(error))


def check_foxglove(source, recording, episodes):
    """Foxglove's own ROS 2 deserializer (tests/record/read_mcap.mjs) decodes every frame of the
    camera channel: PNG bytes, stamped with the observation's time."""
    done = subprocess.run(["node", f"{source}/tests/record/read_mcap.mjs", recording,
                           "--messages", "1000000"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    messages = json.loads(done.stdout)["messages"]["/comply/camera/front"]
    assert len(messages) == EPISODES * (STEPS + 1), len(messages)
    # Each episode's frames 50 ms apart on the recording's clock, as the observations were.
    stamps = [int(m["data"]["header"]["stamp"]["sec"]) * 10**9
              + int(m["data"]["header"]["stamp"]["nanosec"]) for m in messages]
    for e, episode in enumerate(episodes):
        own = np.array(stamps[e * (STEPS + 1):(e + 1) * (STEPS + 1)]) - stamps[e * (STEPS + 1)]
        observed = np.array([t for t, _ in episode]) - episode[0][0]
        np.testing.assert_allclose(own * 1e-9, observed, atol=1e-9)
    for message in messages:
        image = message["data"]
        assert image["format"] == "png" and image["data"][:4] == [137, 80, 78, 71], image["format"]
        assert image["header"]["frame_id"] == "front"


def read_parquet(source, script, path):
    done = subprocess.run(["node", f"{source}/tests/export/{script}", path],
                          capture_output=True, text=True)
    assert done.returncode == 0, (
        f"{script} failed on {path}: {done.stderr} (scripts/install-deps.sh installs Node's "
        "packages)")
    return json.loads(done.stdout)


def floats(value):
    return np.array([np.nan if v is None or v == "NaN" else float(v) for v in value],
                    dtype=np.float32)


def in_force(stamps_ns, first_ns, t_s):
    """The row of the last record stamped at or before first_ns + t_s (1 ns tolerance)."""
    return int(np.searchsorted(stamps_ns - first_ns, t_s * 1e9 + 1.0, side="right")) - 1


def check_rows(rows, cycles, episode_rows):
    """Every row against the cycle record in force at its time."""
    stamps = (cycles["state.header.stamp.sec"].astype(np.int64) * 1_000_000_000
              + cycles["state.header.stamp.nanosec"].astype(np.int64))
    starts = list(np.flatnonzero(cycles["state.cycle"] == 0)) + [len(stamps)]
    assert len(starts) == EPISODES + 1, starts
    position = cycles["state.position"]
    command = cycles["cartesian_in_force.position"]
    stiffness = cycles["cartesian_in_force.stiffness_translational"]
    frame_q = cycles["cartesian_in_force.task_frame"]
    for e, (begin, end) in enumerate(episode_rows):
        first, last = starts[e], starts[e + 1]
        own = stamps[first:last]
        for i, row in enumerate(rows[begin:end]):
            assert int(row["frame_index"]) == i and int(row["episode_index"]) == e, row
            assert np.float32(row["timestamp"]) == np.float32(i / FPS), (i, row["timestamp"])
            k = first + in_force(own, own[0], i / FPS)
            np.testing.assert_array_equal(floats(row["observation.state"]),
                                          position[k].astype(np.float32))
            np.testing.assert_array_equal(floats(row["action"])[:3],
                                          command[k].astype(np.float32))
            np.testing.assert_array_equal(floats(row["action.stiffness"])[:9],
                                          stiffness[k].astype(np.float32))
            np.testing.assert_array_equal(floats(row["action.task_frame"]),
                                          frame_q[k].astype(np.float32))
    # The stiffness changed along the episode: the comparison could fail.
    assert len({tuple(floats(r["action.stiffness"])) for r in rows}) > 3


def check_stats(dataset, rows):
    """meta/stats.json's numeric features against numpy over the rows a reader gave."""
    with open(os.path.join(dataset, "meta", "stats.json")) as file:
        stats = json.load(file)
    for feature in ("observation.state", "action", "action.stiffness", "timestamp", "index"):
        values = np.array([floats(np.atleast_1d(row[feature])) for row in rows], dtype=np.float64)
        np.testing.assert_allclose(stats[feature]["mean"], values.mean(axis=0), rtol=1e-9,
                                   atol=1e-12, err_msg=feature)
        np.testing.assert_allclose(stats[feature]["std"], values.std(axis=0), rtol=1e-7,
                                   atol=1e-9, err_msg=feature)
        np.testing.assert_array_equal(stats[feature]["min"], values.min(axis=0), err_msg=feature)
        np.testing.assert_array_equal(stats[feature]["max"], values.max(axis=0), err_msg=feature)
        assert stats[feature]["count"] == [len(rows)], feature


def decoded_frames(video):
    raw = subprocess.run(["ffmpeg", "-v", "error", "-i", video, "-f", "rawvideo", "-pix_fmt",
                          "rgb24", "-"], capture_output=True, check=True).stdout
    return np.frombuffer(raw, dtype=np.uint8).reshape(-1, HEIGHT, WIDTH, 3).astype(np.float64)


def check_video(dataset, info, episodes, episode_table):
    video = os.path.join(dataset, info["video_path"].format(
        video_key="observation.images.front", chunk_index=0, file_index=0))
    probe = json.loads(subprocess.run(
        ["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
         "stream=nb_read_frames,width,height,codec_name", "-of", "json", video],
        capture_output=True, text=True, check=True).stdout)["streams"][0]
    assert int(probe["nb_read_frames"]) == info["total_frames"], probe
    assert (probe["width"], probe["height"], probe["codec_name"]) == (WIDTH, HEIGHT, "h264")
    frames = decoded_frames(video)
    assert len(frames) == info["total_frames"]
    # meta/stats.json: the camera's per channel on 0 to 1, of the frames as decoded.
    with open(os.path.join(dataset, "meta", "stats.json")) as file:
        stats = json.load(file)["observation.images.front"]
    np.testing.assert_allclose(np.array(stats["mean"]).ravel(),
                               frames.mean(axis=(0, 1, 2)) / 255.0, rtol=1e-9)
    np.testing.assert_allclose(np.array(stats["std"]).ravel(),
                               frames.std(axis=(0, 1, 2)) / 255.0, rtol=1e-6)
    np.testing.assert_array_equal(np.array(stats["max"]).ravel(),
                                  frames.max(axis=(0, 1, 2)) / 255.0)
    assert np.array(stats["mean"]).shape == (3, 1, 1) and stats["count"] == [len(frames)]
    for e, episode in enumerate(episode_table):
        begin, end = int(episode["dataset_from_index"]), int(episode["dataset_to_index"])
        assert episode["videos/observation.images.front/from_timestamp"] == begin / FPS
        assert episode["videos/observation.images.front/to_timestamp"] == end / FPS
        times = np.array([t for t, _ in episodes[e]]) - episodes[e][0][0]
        images = np.stack([image for _, image in episodes[e]]).astype(np.float64)
        for i in range(end - begin):
            expected = int(np.searchsorted(times, i / FPS + 1e-9, side="right")) - 1
            error = np.abs(images - frames[begin + i]).mean(axis=(1, 2, 3))
            # Lossy coding: the right image is the nearest one (ties: frames at rest).
            assert error[expected] <= error.min() + 0.25, (e, i, expected, error)
            assert error[expected] < 4.0, (e, i, error[expected])


def main():
    cli, source = sys.argv[1], sys.argv[2]
    check_cameras(source)
    with tempfile.TemporaryDirectory() as folder:
        recording = os.path.join(folder, "run.mcap")
        episodes = run_sim(source, recording)
        images = comply.read_recording(recording)["/comply/camera/front"]
        assert images.count == EPISODES * (STEPS + 1), images.count
        assert set(images["format"]) == {"png"}
        check_foxglove(source, recording, episodes)

        dataset = os.path.join(folder, "dataset")
        done = subprocess.run([cli, "export", "--lerobot", dataset, recording, "--fps", str(FPS),
                               "--task", "reach"], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr
        with open(os.path.join(dataset, "meta", "info.json")) as file:
            info = json.load(file)
        feature = info["features"]["observation.images.front"]
        assert feature["dtype"] == "video" and feature["shape"] == [HEIGHT, WIDTH, 3], feature
        assert info["total_episodes"] == EPISODES

        data = os.path.join(dataset, "data", "chunk-000", "file-000.parquet")
        episode_file = os.path.join(dataset, "meta", "episodes", "chunk-000", "file-000.parquet")
        episode_table = read_parquet(source, "read_parquet.mjs", episode_file)["rows"]
        episode_rows = [(int(e["dataset_from_index"]), int(e["dataset_to_index"]))
                        for e in episode_table]
        cycles = comply.read_recording(recording)["/comply/cycle"]
        for script in ("read_parquet.mjs", "read_parquet_duckdb.mjs"):
            table = read_parquet(source, script, data)
            assert table["num_rows"] == info["total_frames"] == len(table["rows"]), script
            check_rows(table["rows"], cycles, episode_rows)
        check_stats(dataset, table["rows"])
        check_video(dataset, info, episodes, episode_table)
        print(f"ok: {EPISODES} episodes, {info['total_frames']} rows and video frames at {FPS} "
              "fps, read by hyparquet, DuckDB and ffprobe; frames by Foxglove's deserializer")


if __name__ == "__main__":
    main()
