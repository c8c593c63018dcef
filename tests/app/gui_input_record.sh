# Cases of gui_input.sh (sourced by it, which sets the helpers and variables they use):
# Recording from the Export panel: a PNG folder, with the plot window open, an MP4 movie, a GIF, and an
# MP4 ended by Ctrl-C in the terminal.

input_case_record_png() {
  record "$work/frames"
  count=$(ls "$work/frames" | grep -c '^frame_[0-9]*\.png$')
  ((count == recorded)) || fail "$count PNG files for $recorded frames recorded"
  for f in "$work"/frames/frame_*.png; do
    [[ "$(head -c 8 "$f" | od -An -tx1 | tr -d ' \n')" == 89504e470d0a1a0a ]] || fail "$f is not a PNG"
  done
  if [[ -n "$png_check" ]]; then
    "$png_check" "$work/frames/frame_000003.png" --overlay || fail "frame 3 is not a picture with the overlay"
    "$png_check" "$work/frames/frame_000003.png" --no-plot || fail "frame 3 has a plot, with the plot window closed"
  fi
}

input_case_record_plot() {
  # the plot window open while recording: the frames carry its plot (kinetic energy against
  # time), as `run --plot` draws it
  WITH_PLOT=1 record "$work/frames"
  [[ "$(state plot_series)" == kinetic ]] || fail "the plot shows $(state plot_series), not kinetic"
  count=$(ls "$work/frames" | grep -c '^frame_[0-9]*\.png$')
  ((count == recorded)) || fail "$count PNG files for $recorded frames recorded"
  if [[ -n "$png_check" ]]; then
    "$png_check" "$work/frames/frame_000004.png" --plot || fail "frame 4 has no plot"
    "$png_check" "$work/frames/frame_000004.png" --overlay || fail "frame 4 is not a picture with the overlay"
  fi
}

input_case_record_mp4() {
  # in a 1024x768 window (a projector): the panel column scrolls to the buttons
  record "$work/movie.mp4" --size 1024x768
  [[ "$(state window)" == "1024 768" ]] || fail "window $(state window), asked 1024x768"
  frames=$(movie_frames "$work/movie.mp4")
  ((frames == recorded)) || fail "the movie has $frames frames, the window recorded $recorded"
  size=$(ffprobe -v error -select_streams v:0 -show_entries stream=width,height -of csv=p=0:s=x "$work/movie.mp4")
  [[ "$size" == 1024x768 ]] || fail "movie frames of $size, the window is 1024x768"
}

input_case_record_gif() {
  # a GIF for slides, its format by the name typed: every frame recorded in it, and the
  # temporary file it was written under renamed, not left beside it
  record "$work/movie.gif"
  frames=$(movie_frames "$work/movie.gif")
  ((frames == recorded)) || fail "the GIF has $frames frames, the window recorded $recorded"
  [[ "$(ffprobe -v error -select_streams v:0 -show_entries stream=codec_name -of csv=p=0 "$work/movie.gif")" == gif ]] ||
    fail "movie.gif is not a GIF"
  ! ls -A "$work" | grep -q '\.part$' || fail "a temporary .part file was left beside the GIF"
}

input_case_record_interrupted() {
  # Ctrl-C in the terminal that started the window, while it records: the window closes, the
  # movie is finished with every frame recorded, exit code 130
  begin_record "$work/movie.mp4"
  kill -INT "$pid"
  end=$((SECONDS + 30))
  while kill -0 "$pid" 2>/dev/null; do
    ((SECONDS < end)) || fail "the program did not exit within 30 s of SIGINT"
    sleep 0.1
  done
  wait "$pid"
  code=$?
  pid=""
  ((code == 130)) || fail "exit code $code after SIGINT, expected 130"
  grep -q "the window was closed by SIGINT" "$log" || fail "no word of the signal in the log"
  recorded=$(recorded_frames)
  [[ -n "$recorded" ]] && ((recorded >= 5)) || fail "the log reports no recording of 5 frames or more"
  frames=$(movie_frames "$work/movie.mp4")
  ((frames == recorded)) || fail "the movie has $frames frames, the window recorded $recorded"
}
