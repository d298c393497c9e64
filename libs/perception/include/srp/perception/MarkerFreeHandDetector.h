#pragma once
/// \file MarkerFreeHandDetector.h
/// \brief The bare hand without a marker: depth foreground against the
/// hand-free first frames, skin colour, and connection to the image border
/// where the arm enters; the palm centre from the arm's geometry (its axis and
/// the wrist at the cuff), not from any marker.

#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/perception/HandDetector.h"
#include "srp/perception/PlaneFit.h"

namespace srp::perception {

class CameraMotionEstimator;

/// Marker-free hand detector (no tag is decoded or used as a feature: it works
/// on a plain glove, a bare hand in a sleeve, or a bare forearm).
///
/// Background, two ways:
/// - whole recording (when the caller showed every frame to preview() first,
///   as DemoPerception does): per pixel, the `backgroundPercentile` quantile of
///   the valid depths of up to `maxBackgroundSamples` frames spread over the
///   recording (the depth behind whatever moves: a demonstrator in view from
///   the first frame, whose arm and torso move, is foreground), and the mean
///   colour;
/// - first frames (no preview, a stream): the per-pixel median depth and mean
///   colour of the first `backgroundFrames` frames, which must show no hand.
///
/// A moving camera (a head-mounted one sways with the head; `followCameraMotion`):
/// the preview estimates every frame's camera pose from its depth
/// (CameraMotionEstimator: point-to-plane ICP against key frames). When the
/// camera moved (minCameraMotion_m, minCameraTurn_deg), each background sample is warped into the first frame's
/// camera (its image widened by `movingBackgroundMargin` on every side, so
/// that what the camera saw only later has a background too) before the
/// per-pixel quantile, and each frame's background is that one warped into the
/// frame's own camera (nearest surface per pixel, gaps narrower than
/// movingBackgroundGap filled from behind). A pixel where no background lands
/// is no foreground (farWithoutDepth does not apply), and the still-arm rule is
/// not used: an arm in view in every frame enters through the background that
/// stands above the support plane at the border (enterThroughStillArm).
///
/// Skin colour, adapted per recording: a Gaussian in (Cr, Cb) fitted to the
/// foreground pixels inside a broad prior box (`skinPrior*`, luma >=
/// `skinMinLuma`): the histogram's mode and the pixels within `skinModeRadius`
/// of it (the demonstrator's dominant skin tone; a shirt, a toy's face or a
/// table of a skin-like colour fall outside it). Learnt from the preview
/// samples (at least `minSkinSamples` pixels) and used when the recording
/// shows a bare forearm (step 4); otherwise (a glove and sleeve, or no
/// preview) the prior box itself, with which the cuff rule's lengths were
/// measured.
///
/// Per frame (pixels of the colour image, registered depth):
/// 1. foreground = closer than the background by `minForeground_m`, or a
///    depth hole where the colour changed by more than `holeColourChange`
///    (the moving hand's holes: on a ToF camera more than half of the hand has
///    no depth);
/// 2. the arm = the largest foreground component touching the border (where
///    it enters; a demonstrator's whole body): the image edge, or where the
///    depth's field of view ends inside a registered image, this frame's
///    depth-less band at the edge (`minFieldOfViewValid`; nothing outside the
///    field of view is foreground);
/// 3. the hand = its skin-coloured part, holes filled (a held object, a
///    badge); the sleeve = the largest non-skin part of the arm that reaches
///    the border (a carried object does not);
/// 4. bare forearm: when the skin component reaching farthest from the
///    border along the geodesic inside the arm (`geodesicStep_px`; 0: the
///    largest skin component) is longer than
///    `maxHandLength_m` between the ends of its principal axis (in 3D; skin
///    from the elbow or a short sleeve to the fingers), the hand is its far
///    end: the axis end
///    farther from the arm's entry (the body); its last `maxHandLength_m`
///    give the hand's own axis and centre line, and the palm centre lies
///    `palmFromFarEnd_m` back from the far end along it. With a preview, a
///    recording whose samples show such a forearm in at least
///    `bareForearmFraction` of them uses this rule in every frame;
/// 5. else the wrist = the cuff line, the hand's pixels next to the sleeve;
///    the arm axis = principal direction of sleeve + hand, pointing inwards;
///    the palm centre = the wrist plus `palmFromWrist_m` along the axis
///    (a fixed length of the hand: it does not move when the fingers close
///    round an object, unlike the blob's centre or its thickest point);
/// 6. no cuff in view (the skin itself reaches the border while the hand
///    enters or leaves, or no sleeve): the palm centre lies
///    `palmFromFingertips_m` back from the fingertips along the hand's
///    principal axis (the inward border normal for a short blob), on the
///    hand's centre line; it may lie outside the image;
/// 7. depth: median of the valid depth on the hand within `palmRadius_m` of
///    the palm pixel, plus `palmDepth_m` (the palm centre lies inside the
///    hand, below its visible back), more where the hand's silhouette there
///    is narrower than the palm (`palmHalfWidth_m`: the hand seen on its
///    edge, from the side). None there (a hole, or the palm out of
///    view): `hasDepth = false` when the last palm depth is at most
///    `maxCarryFrames` frames old (the caller carries it along the palm's ray,
///    see DemoPerception; `palm_px` is placed for that depth), else the whole
///    hand's valid depth, else `hasDepth = false`.
///
/// The palm is placed in metres: the anchor pixel (far end, cuff or
/// fingertips) back-projected at the palm's depth, plus the length along the
/// axis. State across frames: the background, the skin model and the last
/// palm depth with its age (no smoothing: each palm is measured in its own
/// frame). Hand lengths default to srp::synth's demonstrator (a glove and a
/// sleeve, 7 cm wide) and, for the bare forearm, to an adult hand grasping
/// from above; a real demonstrator's hand size sets them.
/// SRP_HAND_TRACE=1 prints the skin model, the bare-forearm decision and each
/// frame's skin component to stderr (for tuning on a new recording).
class MarkerFreeHandDetector : public HandDetector {
 public:
  struct Options {
    /// First-frames background (no preview): frames without the hand.
    int backgroundFrames = 10;
    /// Whole-recording background: quantile (0..1) of each pixel's valid
    /// depths over the samples. High: the depth behind what moves, as long as
    /// the pixel is free in more than (1 - quantile) of the recording.
    double backgroundPercentile = 0.9;
    /// Frames at least twice this wide are shrunk, before anything else, by
    /// the largest whole factor that leaves them at least this wide (colour by
    /// area averaging, depth by each block's middle pixel, the intrinsics with
    /// them); the palm, lastMask() and lastGeometry() are mapped back to the
    /// frame's own pixels, the palm's 3D position is the same either way. A
    /// 1920x1080 colour frame with 640x480 depth re-projected into it (`srp
    /// import` of a RealSense) is worked on at 960x540, ~4 times less CPU
    /// (perception README: egocentric-held-sr300 96.7 -> 99.2 % within 40 px;
    /// shrunk to 640 px wide, 83.0 %); 640x480 and 1280x720 frames keep their
    /// size. 0: every frame at its own size [px].
    int minWorkingWidth_px = 960;
    /// Whole-recording background: at most this many frames are kept,
    /// evenly spread over the recording (memory: 0.6 MB each at 640x480).
    int maxBackgroundSamples = 48;
    /// Whole-recording background: a pixel with valid depth in fewer than
    /// this share of the samples (the shadow band a depth sensor leaves along
    /// a static object's edge, valid only while an arm covers it) takes the
    /// farthest background of its trusted neighbours within
    /// backgroundFillDiameter_px when that lies behind its own quantile
    /// (which would be the arm); with no trusted neighbour it keeps its own
    /// [0..1]. 0: off.
    double minBackgroundValidFraction = 0.5;
    /// Window of that neighbour fill [px].
    int backgroundFillDiameter_px = 9;
    /// Such a pixel with no trusted neighbour (a wide region without depth
    /// most of the time: a wall beyond the sensor's range, seen from the side
    /// or from the demonstrator's head) has no background depth, and
    /// whatever has a depth there is foreground (the arm reaching in front
    /// of it), instead of its own quantile (which is the arm's depth where
    /// only the arm ever gave one). false: its own quantile.
    bool farWithoutDepth = true;
    /// Whole-recording background: an arm that stays in view and nearly
    /// still is its own quantile there. Where the background stands above the
    /// support plane (RANSAC over the background's cloud) by between
    /// minForeground_m and stillArmMaxHeight_m, is of skin colour (the prior
    /// box) in at least stillArmSkinFraction of the samples, that region
    /// reaches the border of the view (where an arm enters), and it is shaped
    /// like an arm (stillArmShapeShare), the background is the plane instead.
    /// A part on the table of skin colour reaches no border and stays
    /// background; a face far above the table is higher; the demonstrator's
    /// trousers or a box of skin-like colour at the border are not shaped
    /// like a forearm.
    bool stillArmFromPlane = true;
    /// That height limit above the support plane [m] (a forearm resting on or
    /// held over the table, not the demonstrator's face).
    double stillArmMaxHeight_m = 0.35;
    /// That share of the samples with colour [0..1].
    double stillArmSkinFraction = 0.9;
    /// Those regions are joined across gaps up to this wide before the
    /// border test (an arm that moved a little over the recording is in every
    /// sample only where it is wide, the hand and the forearm, not at the
    /// wrist between them) [m].
    double stillArmBridge_m = 0.08;
    /// ... and such a region is an arm only when, in at least
    /// stillArmShapeShare of the samples, the skin standing in that height
    /// band that overlaps it (the arm as the sample shows it) is shaped like a
    /// forearm with its hand: as wide as stillArmMinWidth_m to
    /// stillArmMaxWidth_m (from its depth) in at least stillArmWidthShare of
    /// its slices of stillArmSlice_m along its length, and at least
    /// stillArmMinElongation times longer than its median width. 0: any
    /// region at the border.
    double stillArmShapeShare = 0.5;
    /// A forearm's width, wrist to elbow (and a hand's, without the thumb) [m].
    double stillArmMinWidth_m = 0.05, stillArmMaxWidth_m = 0.14;
    /// That share of the slices [0..1].
    double stillArmWidthShare = 0.6;
    /// Slices across the arm's length [m].
    double stillArmSlice_m = 0.02;
    /// Length over median width [ratio].
    double stillArmMinElongation = 2.0;
    /// Whole-recording background under a moving camera (see the class
    /// comment): the preview estimates each frame's camera pose and, when the
    /// camera moved farther than minCameraMotion_m and turned more than
    /// minCameraTurn_deg from the first frame, the background follows the
    /// camera. false: the per-pixel background of a still camera in every
    /// recording.
    bool followCameraMotion = true;
    /// Below these a still camera's background is kept: a camera moved by
    /// less than minForeground_m, or turned by less than the angle that moves
    /// a point 1 m away by that much, changes no depth by more than the
    /// foreground threshold (and the pose's noise on a still camera, depth
    /// noise of 3 mm at 1 m on HRT1, reaches 1 cm and 0.3 deg) [m, deg].
    double minCameraMotion_m = 0.02;
    double minCameraTurn_deg = 1.15;
    /// ... and when the preview samples disagree (depth differs by more
    /// than minForeground_m) with the background warped into their view in
    /// less than this share of the pixels where they disagree with a still
    /// camera's background (a motion that ICP reports on a scene of little
    /// structure, a plane and a large arm, and never was) [ratio].
    double maxMovingDisagreement = 0.5;
    /// That background's image is the first frame's widened by this share of
    /// its width and height on each side [ratio].
    double movingBackgroundMargin = 0.15;
    /// That background's colour is the mean of the samples whose warped depth
    /// lies within minForeground_m of the background's there (the surface, not
    /// the arm or the part that passed over it; where none does, of all that
    /// landed there). A depth hole is foreground by its colour: the band
    /// beside the arm that a depth camera beside the colour camera does not
    /// see is then no foreground. false: the mean of all.
    bool backgroundColourFromSurface = true;
    /// That background's gaps narrower than this share of the image's width,
    /// where no sample had a depth (a depth camera registered to a larger
    /// colour image leaves a band of 2-3 of its pixels without depth along
    /// every depth edge, the same in every sample: 6-9 px at 1920 px from a
    /// 640-px depth), take the farthest depth and the brightest colour around
    /// them; else the arm crossing such an edge (the table's near edge) is
    /// cut there, for a pixel without background is not foreground. 0: off.
    double movingBackgroundGap = 0.015;
    /// That background, warped into a frame's camera, is the nearest within
    /// this many pixels (the estimated camera pose's error; a surface seen at
    /// a grazing angle changes its depth by centimetres per pixel) [px]. 0: off.
    int movingBackgroundSlack_px = 3;
    /// Under a moving camera: an arm in view in every frame, entering at the
    /// same border (a hand held in front of a head-mounted camera), is in
    /// most samples where it enters, and the background there is the arm
    /// itself: the moving arm is foreground only farther in and reaches no
    /// border. The arm then enters the view through the background that stands
    /// above the support plane (fitted to the first camera's widened
    /// background) by minForeground_m to stillArmMaxHeight_m, or that has no
    /// background, where that region reaches the image border: borderZone
    /// takes its pixels. false: the image border only.
    bool enterThroughStillArm = true;
    /// Foreground: closer than the background by this much [m].
    double minForeground_m = 0.02;
    /// Foreground in a depth hole: sum of |BGR| changes from the background
    /// colour (skin over a beige table differs by ~60, sensor noise by ~5).
    int holeColourChange = 30;
    bool useSkin = true;
    /// Skin prior box in YCrCb (8-bit), where the recording's skin model is
    /// looked for; also the skin test until the model is learnt.
    int skinPriorCrMin = 135, skinPriorCrMax = 180, skinPriorCbMin = 80, skinPriorCbMax = 130;
    /// Below this luma (8-bit Y) chroma is noise (black clothes, backlit
    /// faces): never skin.
    int skinMinLuma = 25;
    /// Learnt skin: the luma floor is this share of the recording's skin
    /// luma (mean of its mode) instead of skinMinLuma, so that it follows the
    /// exposure, the light and the person [ratio]; 0: skinMinLuma.
    double skinLumaFloorFraction = 0.5;
    /// ... but never below this luma, where the chroma of 8-bit JPEG is noise [8-bit Y].
    double skinNoiseLuma = 10.0;
    /// Skin model: pixels within this (Cr, Cb) distance of the histogram's
    /// mode [8-bit units] give the Gaussian's mean and covariance.
    double skinModeRadius = 8.0;
    /// Skin = Mahalanobis distance to the Gaussian below this [sigma].
    double skinMaxMahalanobis = 3.0;
    /// Bare forearm (learnt skin): arm pixels within this wider distance
    /// [sigma] join the skin they are connected to on the arm (hysteresis:
    /// a forearm in shadow, sensor noise or JPEG blocks fragment the strict
    /// skin). At most skinMaxMahalanobis: off.
    double skinGrowMahalanobis = 0.0;
    /// Learnt skin: each pixel's colour is the mean over this square
    /// neighbourhood before the skin test [px] (noise, JPEG blocks). <= 1: off.
    int skinColourBlur_px = 0;
    /// Pixels the skin model needs before it replaces the prior box.
    int minSkinSamples = 500;
    int minPixels = 300;
    /// Palm centre below the visible back of the hand along the ray [m]
    /// (half the palm's thickness: srp::synth's glove 11.5 mm, its back 2 mm
    /// higher).
    double palmDepth_m = 0.0125;
    /// Half the palm's width across its axis (srp::synth's glove 42 mm; an
    /// adult's hand breadth is 75-95 mm) [m]. The palm's cross-section is
    /// taken for an ellipse of half-axes palmHalfWidth_m and palmDepth_m; seen
    /// from a direction that narrows its silhouette to a half-width h (a hand
    /// seen from the side, on its thumb or little-finger edge), the palm
    /// centre lies palmHalfWidth_m palmDepth_m / h behind the surface along
    /// the ray (palmDepth_m face-on, up to palmHalfWidth_m edge-on), not
    /// palmDepth_m. h: the median, over the cross-sections across the axis
    /// within palmRadius_m of the palm, of the run of hand pixels through the
    /// palm's centre line (where the centre line lies beside the hand, the
    /// nearest run on its one side), at the palm's depth; a cross-section
    /// whose centre line is off the hand with hand on both sides (a tag or a
    /// badge cut out of the skin) is none: the skin beside it is no whole
    /// palm. Not measured where a run reaches the edge of the view (cut, not
    /// narrow). 0: off (palmDepth_m always).
    double palmHalfWidth_m = 0.042;
    /// That width is measured only when at least this share of the
    /// cross-sections within palmRadius_m of the palm are such runs (else
    /// palmDepth_m: a tag or a badge over the palm leaves one or two, whose
    /// width is noise) [0..1].
    double minPalmCrossSections = 0.5;
    /// Palm centre from the wrist (cuff line) along the arm axis, in the
    /// plane of the hand [m].
    double palmFromWrist_m = 0.13;
    /// Radius of the palm disc whose valid depth gives the palm depth [m].
    double palmRadius_m = 0.03;
    /// Without a wrist in view: palm centre back from the fingertips along the
    /// hand's axis [m] (relaxed fingers, as when the hand enters or leaves).
    double palmFromFingertips_m = 0.125;
    /// A skin component longer than this between its ends (in 3D, from
    /// their depths) is a bare forearm with its hand, not a hand: an adult
    /// hand, wrist crease to fingertip, is 0.17-0.21 m, srp::synth's glove
    /// from its cuff to relaxed fingertips 0.255 m, a forearm alone ~0.25 m [m].
    double maxHandLength_m = 0.28;
    /// Whole recording: when the longest skin component is longer than
    /// maxHandLength_m in at least this share of the preview samples that
    /// show skin, the demonstrator's forearms are bare and every frame uses
    /// the far-end rule (a forearm in shadow, too dark for skin, leaves only
    /// the hand: its skin boundary is no sleeve's cuff).
    double bareForearmFraction = 0.2;
    /// Bare forearm: palm centre back from the arm's far end along the hand's
    /// axis [m] (half a palm plus the curled fingers of a hand grasping from
    /// above, 0.05 + 0.02 m).
    double palmFromFarEnd_m = 0.07;
    /// Bare forearm, by the view: the palm's distance back from the far end follows the angle between
    /// the hand's axis (on its depth profile, as the palm is walked) and the camera's ray at the far end:
    /// palmFromFarEndAlongRay_m when the hand points along the ray (seen from above and behind: the far
    /// end is the curled fingers seen end-on, near the palm), palmFromFarEndAcrossRay_m when it lies
    /// across it (from the side, across the table: the far end is the fingers hanging or stretched out
    /// of the palm), linear in |cos| between [m]. Both > 0: this rule instead of palmFromFarEnd_m for a
    /// far end read closed. Chosen on the development renders: 0.045 and 0.12 m; 0 (off) because the
    /// real HRT1 hands, closed and seen from beside the table, lie across the ray with their curled
    /// fingers at the far end (perception README).
    double palmFromFarEndAlongRay_m = 0.0;
    double palmFromFarEndAcrossRay_m = 0.0;  ///< see palmFromFarEndAlongRay_m [m]
    /// Bare forearm: tell an open hand from a closed one. A hand joined to
    /// foreground that is not skin reaching past the skin's far end by more
    /// than palmRadius_m holds a part and is closed. Else by where the hand is
    /// thickest (the distance transform's maximum in metres, each pixel at
    /// its own depth, within maxHandLength_m of the far end in 3D) and where
    /// it is broadest (its skin across the axis per centimetre along it, on
    /// the hand's depth line): both past the middle of palmFromFarEnd_m and
    /// palmFromFingertips_m (the thickest within palmRadius_m beyond the
    /// latter), with the skin behind the thickest point narrower
    /// (maxWristToPalm), the far end is an open hand's fingertips (reaching,
    /// retracting) and the palm lies palmFromFingertips_m back from it; else
    /// palmFromFarEnd_m. The breadth keeps a hand hanging from a flexed wrist
    /// (seen from the side, thickest where it joins the forearm, 0.10 m from
    /// its far end, but broadest across its span 0.07 m from it) closed.
    /// false: palmFromFarEnd_m always.
    bool farEndOpenHand = false;
    /// farEndOpenHand: the hand is open only where the skin 2-3 palmRadius_m
    /// behind its thickest point (the wrist, inside the view) is at most this
    /// share of the palm's thickness (an adult's wrist 55-65 mm wide against
    /// a palm breadth of 75-95 mm; srp::synth's glove 62 against 84) [ratio].
    double maxWristToPalm = 0.85;
    /// The skin model and the bare-forearm decision look only at each preview
    /// sample's foreground that reaches the edge of the depth's field of view
    /// (the arm, where it enters, and what it holds): a part standing on the
    /// table before it is grasped or after it is placed is foreground against
    /// the whole-recording background too, and its shaded face may be of skin
    /// colour. false: all the samples' foreground.
    bool skinFromArmOnly = false;
    /// The preview's foreground includes depth holes whose colour changed
    /// from the background's (holeColourChange) and, with farWithoutDepth, a
    /// depth where a still camera's background has none, as each frame's
    /// does: a moving arm on a ToF camera is more hole than depth, and
    /// without them the preview sees it in fragments. false: by depth alone.
    bool holesInPreview = false;
    /// In a recording of bare forearms, skin no longer than a hand
    /// (maxHandLength_m, in 3D) with at least minCuffPixels on the border is
    /// the hand entering or leaving the view with its forearm out of view:
    /// the palm lies back from its fingertips (palmFromFingertips_m), not
    /// from a forearm's far end. false: the far end in every frame.
    bool handFirstAtTheBorder = false;
    /// The last palm depth is carried along the palm's ray for at most this
    /// many frames (the caller does it, see DemoPerception) [frames].
    int maxCarryFrames = 3;
    /// The palm's length from its anchor (palmFromWrist_m, palmFromFarEnd_m,
    /// palmFromFingertips_m) is walked in 3D on the hand's depth profile (a
    /// line fitted to the hand's depths along the axis), not in the image
    /// plane at one depth: a hand seen obliquely (from the demonstrator's
    /// head, from the side) is foreshortened. false: in the image plane.
    bool walkOnDepth = true;
    /// That profile: samples farther than this from the first line fit are
    /// left out of the second (curled fingers, depth edges) [m].
    double tiltInlier_m = 0.02;
    /// That profile needs this many valid depth samples (every
    /// axisStride_px-th pixel), spread over half the length at least [samples].
    int minTiltSamples = 20;
    /// The walk stops at this many times the length in the image plane (a
    /// hand seen almost end-on) [ratio].
    double maxWalkFactor = 2.0;
    /// The palm centre lies palmDepth_m under the visible back of the hand
    /// along the back's normal (the smallest principal direction of the palm
    /// disc's 3D points), not along the camera's ray: a hand seen obliquely.
    /// false: along the ray.
    bool palmAlongNormal = true;
    /// Cuff rule: the palm lies from the cuff towards the hand's thickest
    /// point (the maximum of the distance transform of the hand's mask: the
    /// palm, not a thumb or a finger), not along the principal axis of sleeve
    /// and hand (which perspective turns when the forearm comes at the
    /// camera). false: that axis.
    bool cuffTowardsThickest = true;
    /// Cuff rule: the palm's length is measured from the sleeve's edge at the
    /// cuff when the sleeve is nearer the camera there than the wrist's skin
    /// (the depth of the sleeve's pixels along the cuff line): a sleeve
    /// standing off the wrist hides the wrist's first centimetres from a
    /// camera above and behind the hand (the demonstrator's head), and the
    /// first skin seen lies that much towards the fingers. The hidden length
    /// is the gap from the sleeve's edge to the first skin along the hand's
    /// axis (in 3D, on its depth profile); it is taken off palmFromWrist_m.
    /// false: from the first skin.
    bool cuffAtSleeveEdge = true;
    /// In a recording whose preview shows no bare forearm, a cuff in view
    /// (step 5) places the palm before the bare-forearm rule is tried: a
    /// skin blob longer than a hand next to a sleeve's cuff is the hand and
    /// something of a skin-like colour it holds, whose far end is no hand's.
    /// false: the bare-forearm rule first in every frame.
    bool cuffFirst = true;
    /// That normal is used when the disc is flat: its smallest spread at most
    /// this share of the next [ratio].
    double maxNormalFlatness = 0.25;
    /// Foreground that reaches no border (the forearm out of view or without
    /// depth) is a hand only when at least this share of it is skin: a part
    /// that is moved later is foreground against the whole-recording
    /// background before it moves, and a shaded side of it may be of skin
    /// colour [0..1].
    double minIslandSkinFraction = 0.5;
    /// The arm's skin is closed (a morphological closing, a disc of this diameter at the arm's median
    /// depth) inside the arm before it is opened and its holes filled: thin things worn on the skin
    /// (a sensor rig's wires, tape) cut it into pieces and notch its outline where they reach it. It only
    /// adds skin. Off by default: it also joins an open hand's spread fingers across a part held behind
    /// them, which then reads as a closed hand (perception README). 0: off [m].
    double skinGapClose_m = 0.0;

    // ---- the lamp's colour: the skin model and the island rule see the scene as under a white lamp ----
    /// Skin is judged on the colour divided, channel by channel, by the scene's illuminant (von Kries
    /// scaling), estimated once per recording from its background colour (the preview's mean image, or
    /// the first frames' mean without a preview) as the Minkowski mean of each channel with this exponent
    /// (shades of grey: 1 the grey world, large towards the white patch), the gains scaled so that a grey
    /// keeps its luma. Off by default: the renders' background is mostly a beige table, so the estimate
    /// follows the table's colour as much as the lamp's (white lamps: gains B 1.05-1.11, R 0.95-0.97;
    /// facing's cold lamp reads neutral, its false hands unchanged). 0: off (the camera's colour as it is).
    double skinIlluminantNorm = 0.0;
    /// The prior box's skin (the skin test without a learnt model: a sleeve and glove, the still arm's
    /// and the island's skin) has a chroma of at most this share of its luma: the length of
    /// (Cr - 128, Cb - 128) over Y (8-bit). YCrCb's chroma grows with the brightness, so a dark saturated
    /// colour (a red part's face in the shade of a lamp from the side: Y 36, Cr 158) has a bright skin's
    /// Cr and passes the box, under any lamp; the renders' skin is 0.15-0.3 under white, warm and cold
    /// lamps, a saturated part's 0.8-0.9. Not applied to the learnt model, which is the recording's own
    /// skin under its own lamp (a real camera's skin in dim light reaches 0.7-1.0). 0: off.
    double skinMaxChromaPerLuma = 0.5;

    // ---- gates and strides (were literals; defaults keep the old output) ----
    /// A pixel within this many pixels of the edge of the depth's field of
    /// view is on the border (where the arm enters, where a hand leaves the
    /// view) [px].
    int borderMargin_px = 2;
    /// The depth's field of view in the (registered) image: the rows and
    /// columns where at least this share of the pixels had a depth in some
    /// frame [0..1]. A registered depth image has a band at its edges the
    /// depth camera does not see (HRT1's Fetch camera: ~20 px at the right
    /// and the top), where no frame has a depth; an arm entering there
    /// reaches that band's edge, not the image's, and nothing is foreground
    /// inside the band. Low: a wall beyond the sensor's range (seen from the
    /// side) has a depth only where the arm passed in front of it, and is in
    /// view (with farWithoutDepth).
    double minFieldOfViewValid = 0.1;
    /// Where the depth's field of view ends inside the image, a run of
    /// depth-less pixels from the image edge is that band (where an arm
    /// enters) up to the band's width plus this [px]: the band's inner edge
    /// moves with the depth (parallax between the two cameras: an arm 1 m
    /// away ends 7 px farther out than the wall behind it on HRT1's camera)
    /// and tilts with a rolled camera (HRT1 rolled by 5 degrees needs more
    /// than 16 px);
    /// farther in, pixels lack depth for another reason (a wall beyond the
    /// sensor's range above an arm seen from the side) and the arm's edge
    /// along them is not where it enters. < 0: no limit.
    int maxBandParallax_px = 32;
    /// Bare forearm: the skin component taken for the forearm and hand is the
    /// one reaching farthest from where the body enters the view, along the
    /// geodesic inside the body's foreground, measured on a grid of this many
    /// pixels (trousers, a face, a neck of skin colour lie near where the
    /// body enters; the hand is the far end of the arm over the workspace).
    /// 0: the largest skin component instead.
    int geodesicStep_px = 4;
    /// Bare forearm: the skin component taken for the forearm and hand must
    /// reach at least this far from where the body enters the view, along
    /// that geodesic (at the skin's depth) [m]; else the frame reports no palm
    /// (the face, neck or shoulder near the body's entry, the forearm's skin
    /// lost in dark light). 0: off. Needs geodesicStep_px > 0.
    double minSkinReach_m = 0.10;
    /// Diameter of the disc that opens (de-speckles) the foreground and the
    /// skin masks at full resolution [px].
    int openDiameter_px = 5;
    /// The same in the preview, whose samples are at half resolution [px].
    int previewOpenDiameter_px = 3;
    /// The hand (the arm's skin part) needs at least this many pixels [px].
    int minHandPixels = 150;
    /// A sleeve (the arm's non-skin part at the border) needs more than this
    /// many pixels [px].
    int minSleevePixels = 150;
    /// Preview: the largest skin component of a sample (half resolution)
    /// counts when larger than this many pixels [px at half size].
    int minPreviewSkinPixels = 37;
    /// A cuff line is the wrist when at least this many skin pixels touch the
    /// sleeve, and it is not used when this many skin pixels lie on the
    /// image border (the hand entering or leaving) [px].
    int minCuffPixels = 10;
    /// Principal axes are estimated from every n-th row and column [px].
    int axisStride_px = 2;
    /// A blob's principal direction is used when its variance along it is
    /// more than this times the variance across it [ratio].
    double minElongation = 2.0;
    /// Valid depth pixels a median depth needs (hand, palm disc, arm end) [px].
    int minDepthSamples = 5;
    /// The same for the arm ends in the preview (half resolution) [px].
    int minPreviewDepthSamples = 3;
    /// Confidence 1 when the arm has this many pixels, proportionally less
    /// below [px].
    double confidenceFullArea_px = 3000.0;
    /// Confidence factor of a palm placed without a wrist (far end or
    /// fingertips: the palm's position along the hand is less certain) [0..1].
    double noWristConfidence = 0.5;
    /// Skin histogram smoothing before its mode is taken: Gaussian sigma
    /// (JPEG chroma noise) [8-bit Cr/Cb units].
    double skinHistogramBlur = 2.0;
    /// Trimmed re-estimates of the skin Gaussian inside its
    /// skinMaxMahalanobis ellipse [iterations].
    int skinRefinements = 3;
    /// Skin luma from the mode of the luma histogram of the pixels of skin
    /// chroma (then a trimmed mean and spread around it, within
    /// skinMaxMahalanobis sd) instead of their plain mean and spread: a
    /// bright object of skin chroma (a toy's tan belly, a beige table) forms
    /// a second mode and is left out of this person's skin in this light.
    bool skinLumaFromMode = true;
    /// Luma histogram smoothing before its mode is taken: Gaussian sigma
    /// [8-bit Y units].
    double skinLumaBlur = 3.0;
    /// First luma estimate: the pixels within this distance of the mode
    /// [8-bit Y units].
    double skinLumaModeRadius = 20.0;
    /// A recording with bare forearms, depth lagging colour (a real camera's
    /// streams on a fast arm): how far the colour may lead the depth image
    /// [px] (an arm moving 0.5 m/s, one 10 Hz frame, at 1 m: ~25 px). Skin
    /// within this distance of the arm, off the arm, whose colour changed
    /// from the background colour by more than minLagColourChange, and
    /// connected to skin on the arm, is hand. 0: off.
    int maxDepthLag_px = 30;
    /// Motion prior: once minPalmTrack palms (with depth) were accepted, a
    /// palm that moved across the camera's rays (its pixel shift at its
    /// depth) farther from the last accepted one than this speed times the
    /// time between their frames (RgbdFrame::t_s) is refused (no hand
    /// reported) [m/s]; a demonstrator's hand moves at up to ~1-2 m/s in a
    /// pick and place. 0: off. Image folders get their timestamps from
    /// `srp import --fps`: a wrong rate scales this limit.
    double maxPalmSpeed_mps = 0.0;
    /// Accepted palms before the motion prior applies [frames].
    int minPalmTrack = 3;
    /// After this many refusals in a row the next palm starts a new track
    /// (the track itself may have been wrong) [frames].
    int maxPalmRefusals = 3;
    /// That colour change: sum of |BGR| changes [8-bit units] (a dark hand
    /// over a bright wall: 150-300; a shadow moving on the wall beside the
    /// demonstrator: below ~90).
    int minLagColourChange = 100;
  };

  /// What the last detect() found, in pixels (for drawing and tests).
  struct Geometry {
    bool haveWrist = false;
    bool bareForearm = false;  ///< the palm was placed from the far end of a bare forearm
    Eigen::Vector2d entry_px = Eigen::Vector2d::Zero();  ///< mean of the arm's border pixels
    Eigen::Vector2d wrist_px = Eigen::Vector2d::Zero();  ///< cuff line centre
    Eigen::Vector2d farEnd_px = Eigen::Vector2d::Zero();  ///< bare forearm: its far end
    Eigen::Vector2d axis = Eigen::Vector2d::UnitX();     ///< unit, from the border towards the fingers
    Eigen::Vector2d palm_px = Eigen::Vector2d::Zero();
    /// The palm's anchor (far end, cuff line or fingertips) in the camera frame, at the depth of the hand's
    /// depth profile there [m]; zero without a profile.
    Eigen::Vector3d anchor_camera_m = Eigen::Vector3d::Zero();
    /// Unit, the hand's axis in the camera frame towards the fingers, on its depth profile; zero without one.
    Eigen::Vector3d axis_camera = Eigen::Vector3d::Zero();
    /// Unit, the back of the hand's normal at the palm in the camera frame (towards the camera); zero
    /// without one (palmAlongNormal off, too few depths, not a disc).
    Eigen::Vector3d normal_camera = Eigen::Vector3d::Zero();
    double palmFromAnchor_m = 0.0;  ///< the length walked from the anchor to the palm [m]
  };

  /// The recording's skin model (Gaussian in Cr, Cb).
  struct SkinModel {
    bool learnt = false;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();
    double meanLuma = 0.0, sdLuma = 255.0;  ///< luma (Y) of those pixels; skin lies within skinMaxMahalanobis sd
    int samples = 0;
  };

  explicit MarkerFreeHandDetector(const Options& options);
  /// Keeps a sample of the frame for the whole-recording background and skin
  /// model. Throws InvalidInputError after the first detect().
  void preview(const rawlog::RgbdFrame& frame) override;
  std::optional<HandObservation> detect(const rawlog::RgbdFrame& frame) override;
  std::string name() const override { return "marker-free"; }
  const Options& options() const { return options_; }

  /// Hand mask of the last frame (CV_8UC1, the frame's own size), for drawing.
  const cv::Mat& lastMask() const { return shrink_ > 1 ? lastMaskFull_ : lastMask_; }
  const Geometry& lastGeometry() const { return geometry_; }
  const SkinModel& skinModel() const { return skin_; }
  /// True when the preview found the camera moving and each frame's background follows it (the
  /// whole-recording background warped into the frame's camera); false before the first detect().
  bool followsCamera() const { return cameraMoves_; }

 private:
  /// Palm anchor: the pixel the palm is measured from (far end, cuff line or
  /// fingertips), the unit direction in the image and the signed length
  /// from the anchor to the palm centre along it [m].
  struct Anchor {
    Eigen::Vector2d anchor_px = Eigen::Vector2d::Zero();
    Eigen::Vector2d dir = Eigen::Vector2d::UnitX();
    double length_m = 0.0;
    /// Depth of the anchor when known apart from the hand's own (the sleeve's
    /// edge at the cuff, cuffAtSleeveEdge) [m]; 0: the hand's depth profile there.
    double depth_m = 0.0;
    /// The far end of a bare forearm read as a closed hand (length_m = -palmFromFarEnd_m): the anchor
    /// palmFromFarEndAlongRay_m / palmFromFarEndAcrossRay_m set the length of.
    bool closedFarEnd = false;
  };
  /// The hand's pixels with their depth and pixel scale.
  struct HandBlob {
    cv::Mat mask;             ///< CV_8UC1
    double z_m = 0.0;         ///< median depth of its valid pixels
    double pxPerM = 0.0;      ///< pixels per metre at z_m
  };

  Options options_;
  /// detect() on a frame of the working size (minWorkingWidth_px).
  std::optional<HandObservation> detectAtWorkingSize(const rawlog::RgbdFrame& frame);
  /// `frame` shrunk to the working size (shrink_, set from the first frame), or `frame` itself.
  const rawlog::RgbdFrame& atWorkingSize(const rawlog::RgbdFrame& frame, rawlog::RgbdFrame& shrunk);
  void finishPreview();
  /// Whole-recording background depth [mm, CV_32FC1] from the preview samples
  /// `samples_mm` (also sets backgroundDepth_m_ and backgroundColour_, and
  /// view_ unless `moving`: the samples are warped into the first camera's
  /// widened image, see followCameraMotion).
  cv::Mat backgroundFromPreview(const std::vector<cv::Mat>& samples_mm, bool moving);
  /// Moving camera: the background (canvasDepth_m_, canvasColour_) from the
  /// preview samples warped into the first frame's camera.
  void movingBackgroundFromPreview();
  /// Moving camera: the background as the camera at X_camera0_camera sees it
  /// [m, CV_32FC1; BGR, or no colour when `colour_bgr8` is null]; both reused when of that size.
  void backgroundInView(const core::Pose3& X_camera0_camera, cv::Mat& depth_m, cv::Mat* colour_bgr8) const;
  /// Moving camera, enterThroughStillArm: the pixels of the frame's background
  /// `background_m` [m] seen from X_camera0_camera through which an arm may
  /// enter (CV_8UC1; empty without a support plane). `planeDepth_m`: the
  /// plane's depth [m] where that background stands above it (0 elsewhere).
  cv::Mat enteringBackground(const cv::Mat& background_m, const core::Pose3& X_camera0_camera,
                             cv::Mat* planeDepth_m = nullptr) const;
  /// Moving camera: the camera pose of the previewed frame `index` (the last one used when it was not previewed).
  core::Pose3 previewPose(int index);
  /// stillArmFromPlane: the support plane's depth where the background
  /// `background_mm` [mm, CV_32FC1] is a still arm (in place).
  void stillArmToPlane(cv::Mat& background_mm) const;
  /// stillArmShapeShare: clears `keep` (per label of `labels`, the bridged
  /// regions, with their `stats`) for the regions that are not shaped like an
  /// arm in enough of the samples (`sampleSkin`: sample index and its prior-box
  /// skin mask at half size); `candidate`: the still skin pixels, `plane` the support.
  void keepArmShaped(const Plane& plane, const std::vector<std::pair<std::size_t, cv::Mat>>& sampleSkin,
                     const cv::Mat& labels, const cv::Mat& stats, const cv::Mat& candidate,
                     std::vector<uchar>& keep) const;
  /// Preview sample `i`'s foreground at half size (not opened) [CV_8UC1]: closer than its background
  /// `backgroundHalf_mm` [mm] by depth `depthHalf_mm` [mm, CV_32FC1]; with holesInPreview also its
  /// depth holes whose colour changed from `backgroundColourHalf` (and farWithoutDepth's depth
  /// without a background), inside the field of view; with skinFromArmOnly only its components (once
  /// opened) that reach the edge of the field of view (the arm).
  cv::Mat previewForeground(std::size_t i, const cv::Mat& backgroundHalf_mm, const cv::Mat& depthHalf_mm,
                            const cv::Mat& backgroundColourHalf) const;
  /// Does the preview show a bare forearm (sets bareForearms_)? `foregroundHalf`: each sample's
  /// previewForeground; `depthHalf_mm`: each sample's depth at half size [mm, CV_32FC1].
  void decideBareForearms(const std::vector<cv::Mat>& foregroundHalf, const std::vector<cv::Mat>& depthHalf_mm);
  /// Pixels where an arm enters the view, inside the depth's field of view:
  /// near the image edge, and near this frame's depth-less band where the
  /// field of view ends inside the image (row-major when there is no band).
  std::vector<cv::Point> borderZone(const cv::Mat& depth_m) const;
  /// Foreground by depth (and colour change in depth holes), opened.
  cv::Mat foregroundMask(const rawlog::RgbdFrame& frame) const;
  /// The hand: skin part of the arm, opened, holes filled; empty when too small.
  cv::Mat handMask(const rawlog::RgbdFrame& frame, const cv::Mat& arm) const;
  /// skinGapClose_m: closes `skin` (the arm's skin, CV_8UC1) across narrow gaps inside `arm`.
  void closeSkinGaps(const rawlog::RgbdFrame& frame, const cv::Mat& arm, cv::Mat& skin) const;
  /// The non-skin part of the arm that reaches the border (empty mask: none).
  cv::Mat sleeveMask(const cv::Mat& arm, const cv::Mat& hand) const;
  /// Bare forearm: the largest skin component, when longer than a hand (or
  /// the recording shows bare forearms), ends in the hand at its far end.
  /// Sets geometry_ and replaces `hand` by that component.
  /// `refused`: set when the skin found lies near where the body enters
  /// (minSkinReach_m): the frame reports no palm. `entering`: set when, in a
  /// recording of bare forearms, the skin is no longer than a hand and lies
  /// on the border (handFirstAtTheBorder): the fingertip rule places the palm.
  std::optional<Anchor> bareForearmAnchor(const rawlog::RgbdFrame& frame, const cv::Mat& arm, const Eigen::Vector2d& entry,
                                          HandBlob& hand, bool& refused, bool& entering);
  /// farEndOpenHand: is the hand of skin component `comp` (CV_8UC1) with far end `farEnd_m` (camera
  /// frame [m]) at `farEnd_px`, pointing along `dir`, open (holding nothing that `arm`, the arm's
  /// foreground, shows past the far end; its thickest part past the middle of the two palm lengths,
  /// narrower behind)?
  bool openHandAtFarEnd(const rawlog::RgbdFrame& frame, const cv::Mat& arm, const cv::Mat& comp,
                        const Eigen::Vector3d& farEnd_m,
                        const Eigen::Vector2d& farEnd_px, const Eigen::Vector2d& dir) const;
  /// The label (of `labels`, n labels, their `stats`) of the skin component
  /// of at least minHandPixels that reaches farthest from the border zone
  /// along the geodesic inside `region`; -1 when the region meets no border.
  /// `reachCells`, `bodyReachCells` (optional): that component's and the
  /// region's farthest geodesic distance [cells of geodesicStep_px].
  int farthestSkinComponent(const cv::Mat& region, const cv::Mat& labels, int n, const cv::Mat& stats,
                            int* reachCells = nullptr, int* bodyReachCells = nullptr) const;
  /// Glove and sleeve: the cuff line and the arm axis (nullopt: no cuff).
  std::optional<Anchor> cuffAnchor(const rawlog::RgbdFrame& frame, const cv::Mat& hand, const cv::Mat& sleeve,
                                   const Eigen::Vector2d& entry);
  /// No cuff: back from the fingertips along the hand's axis.
  Anchor fingertipAnchor(const cv::Mat& hand, const Eigen::Vector2d& entry, const Eigen::Vector2d& handMean,
                         const Eigen::Vector2d& handDir, bool elongated) const;
  /// The hand's depth along the anchor's axis as z = c0 + c1 s, s the pixel
  /// distance from the anchor towards the palm [m, m/px]; nullopt when too few depths.
  std::optional<Eigen::Vector2d> handTilt(const rawlog::RgbdFrame& frame, const Anchor& a, const HandBlob& hand) const;
  /// The unit normal, towards the camera, of the 3D points of `mask` within
  /// `radius_px` of `centre_px`; nullopt when too few or not flat.
  std::optional<Eigen::Vector3d> surfaceNormal(const rawlog::RgbdFrame& frame, const cv::Mat& mask,
                                               const Eigen::Vector2d& centre_px, double radius_px) const;
  /// The palm centre's depth behind the hand's surface along the ray [m]:
  /// palmDepth_m, more where the mask's width across `dir` near `palm_px` is
  /// narrower than the palm (palmHalfWidth_m), at `pxPerM` pixels per metre.
  /// `frameIndex`: for the trace.
  double silhouetteDepth(const cv::Mat& mask, const Eigen::Vector2d& palm_px, const Eigen::Vector2d& dir,
                         double pxPerM, int frameIndex) const;
  /// Places the palm from the anchor at the palm's depth (step 7).
  HandObservation placePalm(const rawlog::RgbdFrame& frame, const Anchor& a, const HandBlob& hand,
                            const Eigen::Vector2d& handMean, int armArea);
  /// The pixel `length_m` (>= 0) from anchor `a` along a.dir in 3D, walked on the hand's depth profile
  /// `tilt` (z = tilt(0) + tilt(1) s, s in pixels from the anchor) for at most maxWalkFactor times the
  /// length in the image plane at `pxPerM`.
  Eigen::Vector2d walkOnProfile(const core::CameraIntrinsics& k, const Anchor& a, const Eigen::Vector2d& tilt,
                                double length_m, double pxPerM) const;
  /// palmFromFarEndAlongRay_m: the bare forearm's palm distance back from its far end `farEnd_m`
  /// (camera frame) for the hand's unit axis `axis` (camera frame, on its depth profile) [m].
  double palmFromFarEndByView(const Eigen::Vector3d& farEnd_m, const Eigen::Vector3d& axis) const;
  /// Skin pixels: the learnt model when `learnt` and there is one, else the prior box.
  /// `maxMahalanobis` > 0: this threshold instead of skinMaxMahalanobis.
  cv::Mat skinMask(const cv::Mat& colour_bgr8, bool learnt, double maxMahalanobis = 0.0) const;
  /// Adds the (Cr, Cb) of the foreground pixels inside the prior box.
  void accumulateSkin(const cv::Mat& colour_bgr8, const cv::Mat& foreground, int step);
  void fitSkin();
  /// The skin test's colour space: YCrCb of `colour_bgr8` times skinGains_bgr_ (saturated to 8 bit).
  cv::Mat skinYCrCb(const cv::Mat& colour_bgr8) const;
  /// 255 where a pixel of `ycrcb` is pale enough to be skin (skinMaxChromaPerLuma; 0: everywhere).
  cv::Mat paleEnough(const cv::Mat& ycrcb) const;
  /// Sets skinGains_bgr_ from the recording's background colour (skinIlluminantNorm; 0: unit gains).
  void estimateIlluminant(const cv::Mat& background_bgr8);

  std::vector<cv::Mat> depthHistory_, colourHistory_;
  // Preview: depth samples [mm, CV_16UC1] every previewStride_-th frame, the
  // colour samples at half size, and the colour sum of every frame.
  std::vector<cv::Mat> previewDepth_mm_, previewColour_;
  cv::Mat previewColourSum_;
  int previewFrames_ = 0, previewStride_ = 1;
  cv::Mat skinHistogram_;  ///< 256x256 CV_32F over (Cr, Cb)
  std::vector<cv::Vec3b> skinSamples_;  ///< (Y, Cr, Cb) of the preview's foreground pixels inside the prior box
  SkinModel skin_;
  cv::Scalar skinGains_bgr_{1.0, 1.0, 1.0, 0.0};  ///< von Kries gains from the illuminant (estimateIlluminant)
  core::CameraIntrinsics previewIntrinsics_;
  bool bareForearms_ = false;  ///< the preview showed a bare forearm: the far end rule in every frame
  cv::Mat backgroundDepth_m_, backgroundColour_;
  // Moving camera (followCameraMotion): every previewed frame's index and camera pose in the first
  // frame's camera, each sample's pose, and the background in the first camera's widened image.
  std::shared_ptr<CameraMotionEstimator> previewMotion_;
  std::vector<int> previewFrameIndex_;
  std::vector<core::Pose3> previewSamplePose_;
  bool cameraMoves_ = false;
  cv::Mat canvasDepth_m_, canvasColour_;
  // The support plane in the first frame's camera (none found: nullopt), and this frame's background
  // through which the arm enters (enterThroughStillArm).
  std::optional<Plane> canvasPlane_;
  cv::Mat enteringBackground_;
  core::CameraIntrinsics canvasIntrinsics_;
  std::pair<float, float> canvasDepthRange_m_{0.f, 0.f};  ///< least and greatest valid depth of canvasDepth_m_
  core::Pose3 lastPose_ = core::Pose3::Identity();
  std::size_t nextPose_ = 0;  ///< where previewPose looks first
  cv::Rect view_;  ///< the depth's field of view in the image (depthFieldOfView of the background)
  std::vector<cv::Point> zonePoints_;  ///< this frame's border zone (borderZone)
  cv::Mat lastMask_;
  int shrink_ = 0;         ///< minWorkingWidth_px's factor, from the first frame (0: none seen yet)
  cv::Mat lastMaskFull_;   ///< lastMask_ at the frame's own size when shrink_ > 1
  Geometry geometry_;
  double lastDepth_m_ = 0.0;  ///< last measured depth of the palm's visible back
  int lastDepthFrame_ = 0;    ///< the frameCount_ it was measured in
  int frameCount_ = 0;        ///< frames seen
  Eigen::Vector2d lastPalm_px_ = Eigen::Vector2d::Zero();  ///< last accepted palm with depth
  double lastPalmT_s_ = 0.0;  ///< its frame's timestamp
  int palmTrack_ = 0;         ///< palms accepted since the track (re)started
  int palmRefusals_ = 0;      ///< palms refused in a row
};

}  // namespace srp::perception
