//! Parameters of the four baselines of thesis 3.2 (ICP, KF and their automatic-association
//! modes), in one place so that the per-situation driver and the scan-by-scan step share them
//! without importing each other.

use crate::methods::baselines::cluster_association::CentroidAssociationParams;
use crate::methods::baselines::icp::IcpParams;
use crate::methods::baselines::kalman::KalmanParams;
use crate::methods::baselines::tracker::TrackerParams;

/// Parameters of all baselines.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BaselineParams {
    /// ICP (both modes).
    pub icp: IcpParams,
    /// Kalman filter of `KF`.
    pub kalman: KalmanParams,
    /// Tracker of `KF-AUTO`.
    pub tracker: TrackerParams,
    /// Association of `ICP-AUTO`.
    pub association: CentroidAssociationParams,
}
