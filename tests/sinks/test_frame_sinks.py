"""Frame sinks: orientation, naming, atomic PNG writes, memory and video output."""

import os

import imageio.v3 as iio
import numpy as np
import pytest

from vgxsim.sinks import (
    MemorySink,
    PNGSequenceSink,
    SinkError,
    VideoSink,
    open_sink,
    to_top_down,
    write_image,
    write_png,
)


def bottom_up_image(h=4, w=5, seed=0):
    """An RGBA image whose rows are all different; row 0 is the bottom row."""
    rng = np.random.default_rng(seed)
    img = rng.integers(0, 256, size=(h, w, 4), dtype=np.uint8)
    img[..., 3] = 255
    return img


def test_to_top_down_flips_rows():
    img = bottom_up_image()
    top = to_top_down(img)
    assert np.array_equal(top[0], img[-1]) and np.array_equal(top[-1], img[0])
    assert top.flags["C_CONTIGUOUS"]
    assert to_top_down(img, alpha=False).shape == (4, 5, 3)


def test_rejects_bad_images():
    sink = MemorySink()
    with pytest.raises(TypeError):
        sink.write(np.zeros((2, 2, 4), np.float32))
    with pytest.raises(ValueError):
        sink.write(np.zeros((2, 2), np.uint8))
    with pytest.raises(ValueError):
        sink.write(np.zeros((0, 2, 4), np.uint8))


def test_png_sequence_naming_and_orientation(tmp_path):
    out = tmp_path / "a" / "b"  # created, parents included
    imgs = [bottom_up_image(seed=i) for i in range(3)]
    with PNGSequenceSink(out) as sink:
        for img in imgs:
            sink.write(img)
    names = sorted(os.listdir(out))
    assert names == ["frame_0000.png", "frame_0001.png", "frame_0002.png"]
    assert sink.count == 3 and sink.paths == [str(out / n) for n in names]
    for name, img in zip(names, imgs, strict=True):
        data = iio.imread(out / name)
        assert data.shape == (4, 5, 3)  # RGB by default
        assert np.array_equal(data[0], img[-1, :, :3])  # file's top row = array's last row
        assert np.array_equal(data, img[::-1, :, :3])


def test_png_sequence_prefix_alpha_and_start(tmp_path):
    img = bottom_up_image()
    img[..., 3] = 0  # IRIS programs often leave alpha at 0
    sink = PNGSequenceSink(tmp_path, prefix="shot", digits=2, start=7, alpha=True)
    sink.write(img)
    sink.close()
    data = iio.imread(tmp_path / "shot07.png")
    assert data.shape == (4, 5, 4) and np.array_equal(data, img[::-1])
    with pytest.raises(ValueError):
        sink.write(img)  # closed


def test_image_write_is_atomic(tmp_path, monkeypatch):
    path = tmp_path / "frame_0000.png"
    write_image(path, bottom_up_image(seed=1)[..., :3])
    good = path.read_bytes()

    def broken(fh, image, extension):
        fh.write(b"\x89PNG half")
        raise RuntimeError("disk on fire")

    monkeypatch.setattr(iio, "imwrite", broken)
    with pytest.raises(SinkError, match="frame_0000.png: disk on fire"):
        write_image(path, bottom_up_image(seed=2), overwrite=True)
    assert path.read_bytes() == good  # old file intact
    assert sorted(os.listdir(tmp_path)) == ["frame_0000.png"]  # no temp file left
    sink = PNGSequenceSink(tmp_path / "frames")
    with pytest.raises(SinkError, match="frame_0000.png"):
        sink.write(bottom_up_image(seed=2))
    assert os.listdir(tmp_path / "frames") == [] and sink.count == 0


def test_write_png_single_image(tmp_path):
    img = bottom_up_image(3, 2)
    write_png(tmp_path / "one.png", img)
    assert np.array_equal(iio.imread(tmp_path / "one.png"), img[::-1, :, :3])
    with pytest.raises(SinkError, match="missing"):
        write_png(tmp_path / "missing" / "x.png", img)


def test_unwritable_directory_is_named(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(SinkError, match="file"):
        PNGSequenceSink(blocker / "sub")


def test_memory_sink_keeps_top_down_copies():
    img = bottom_up_image()
    sink = MemorySink()
    sink.write(img)
    img[:] = 0  # later changes to the framebuffer do not leak into stored frames
    sink.write(img)
    assert len(sink) == 2 and sink.count == 2
    assert sink[0].shape == (4, 5, 4)
    assert np.array_equal(sink[0], bottom_up_image()[::-1])
    assert not sink[1].any()


def test_gif_round_trip(tmp_path):
    path = tmp_path / "movie.gif"
    # few flat colours, so the GIF palette reproduces them exactly
    imgs = []
    for i in range(3):
        img = np.zeros((6, 8, 4), np.uint8)
        img[:3] = (255, 0, 0, 255)  # bottom half red
        img[3:] = (0, 0, 255, 255)  # top half blue
        img[0, i] = (0, 255, 0, 255)  # a green pixel on the bottom row, moving
        imgs.append(img)
    with VideoSink(path, fps=10) as sink:
        for img in imgs:
            sink.write(img)
    frames = iio.imread(path, index=None)
    assert frames.shape[:3] == (3, 6, 8)
    for got, img in zip(frames, imgs, strict=True):
        assert np.array_equal(got[..., :3], img[::-1, :, :3])
    assert tuple(frames[0][0, 0, :3]) == (0, 0, 255)  # top row is blue


def test_video_rejects_size_change_and_bad_suffix(tmp_path):
    sink = VideoSink(tmp_path / "v.gif")
    sink.write(np.zeros((4, 4, 4), np.uint8))
    with pytest.raises(ValueError, match="v.gif"):
        sink.write(np.zeros((4, 6, 4), np.uint8))
    sink.close()
    sink.close()  # idempotent
    with pytest.raises(ValueError):
        VideoSink(tmp_path / "v.avi")


def test_video_without_frames_writes_nothing(tmp_path):
    VideoSink(tmp_path / "empty.gif").close()
    assert not (tmp_path / "empty.gif").exists()


def test_mp4_without_ffmpeg_names_the_package(tmp_path, monkeypatch):
    from vgxsim.sinks import mp4

    monkeypatch.setattr(mp4, "ffmpeg_problem", lambda: "no ffmpeg in this test")
    with pytest.raises(ImportError, match="imageio-ffmpeg"):
        VideoSink(tmp_path / "m.mp4")
    assert not (tmp_path / "m.mp4").exists()


def test_mp4_round_trip(tmp_path):
    pytest.importorskip("imageio_ffmpeg")
    path = tmp_path / "m.mp4"
    with VideoSink(path, fps=24) as sink:
        for i in range(5):
            img = np.zeros((15, 17, 4), np.uint8)  # odd size: padded to 16x18
            img[:, :, i % 3] = 200
            sink.write(img)
    frames = iio.imread(path, index=None, plugin="FFMPEG")
    assert frames.shape[0] == 5 and frames.shape[1:3] == (16, 18)


def test_open_sink_chooses_by_spec(tmp_path):
    assert isinstance(open_sink(None), MemorySink)
    mem = MemorySink()
    assert open_sink(mem) is mem
    assert isinstance(open_sink(tmp_path), PNGSequenceSink)
    assert isinstance(open_sink(str(tmp_path / "new_dir")), PNGSequenceSink)
    assert isinstance(open_sink(str(tmp_path / "x.d") + os.sep), PNGSequenceSink)
    gif = open_sink(tmp_path / "a.GIF", fps=12)
    assert isinstance(gif, VideoSink) and gif.fps == 12
    with pytest.raises(ValueError, match="out.png"):
        open_sink(tmp_path / "out.png")
