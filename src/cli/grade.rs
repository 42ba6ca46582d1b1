//! `raylab grade`: a class graded in one command. Each student's image of each scene of the
//! assignment is measured against raylab's ([`raylab::grade`]), and a report a browser opens
//! offline is written (`index.html`, a page per student, `grades.csv`); with `--student`, one
//! folder is graded and its verdicts printed, as a student checks before handing in. The exit
//! status: 0 when it graded (whatever the grades), 1 when the assignment itself is wrong, 2
//! for a mistyped command line.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use raylab::grade::assignment::{Assignment, read_assignment};
use raylab::grade::report::{csv, write_report};
use raylab::grade::submissions::{Student, students};
use raylab::grade::{Measured, StudentGrades, grade};

use super::diff::flip;

#[derive(Args, Debug)]
pub struct GradeArgs {
    /// The assignment (TOML): its scenes, the image a student hands in for each, the
    /// tolerance, the pass mark and the measure. See docs/grading.md.
    assignment: PathBuf,
    /// The submissions: a folder holding one folder per student, named by the student's id.
    #[arg(required_unless_present = "student", requires = "output")]
    submissions: Option<PathBuf>,
    /// The folder the report is written to: index.html, a page per student, grades.csv.
    #[arg(short, long, value_name = "REPORT")]
    output: Option<PathBuf>,
    /// Grade this one student's folder and print its verdicts (no report).
    #[arg(long, value_name = "DIR", conflicts_with_all = ["submissions", "output"])]
    student: Option<PathBuf>,
}

pub fn run(args: GradeArgs) -> Result<(), String> {
    let assignment = read_assignment(&args.assignment).map_err(|e| e.to_string())?;
    let flip = |reference: &_, image: &_| f64::from(flip(reference, image));
    if let Some(folder) = &args.student {
        if !folder.is_dir() {
            return Err(format!("{}: no such folder", folder.display()));
        }
        let id = folder.file_name().map_or_else(
            || folder.display().to_string(),
            |n| n.to_string_lossy().into(),
        );
        let student = Student {
            id,
            folder: folder.clone(),
        };
        let (grades, _) = grade(&assignment, &[student], &flip);
        return super::print_out(|out| write!(out, "{}", verdicts(&assignment, &grades[0])));
    }
    let (Some(submissions), Some(report)) = (&args.submissions, &args.output) else {
        unreachable!("clap requires the submissions and the report without --student");
    };
    let (class, notes) = students(submissions)?;
    for note in notes {
        eprintln!("note: {note}");
    }
    eprintln!(
        "grading {} students on {} scenes of {}",
        class.len(),
        assignment.scenes.len(),
        assignment.name
    );
    let (grades, references) = grade(&assignment, &class, &flip);
    write_report(report, &assignment, &grades, &references)?;
    super::print_out(|out| {
        write!(out, "{}", csv(&assignment, &grades))?;
        writeln!(out, "report: {}", report.join("index.html").display())
    })
}

/// A student's verdicts, a scene a line with what `raylab check` finds in a failed image
/// beneath it, and the total.
fn verdicts(assignment: &Assignment, grades: &StudentGrades) -> String {
    let mut text = String::new();
    let mut possible = 0.0;
    for (scene, grade) in assignment.scenes.iter().zip(&grades.scenes) {
        possible += scene.points;
        let verdict = match &grade.measured {
            Ok(m) => {
                let (word, sign) = if m.passed {
                    ("pass", "≤")
                } else {
                    ("fail", ">")
                };
                format!(
                    "{} {:.4} {sign} {}: {word}",
                    assignment.measure, m.measure, assignment.pass
                )
            }
            Err(problem) => problem.clone(),
        };
        text += &format!(
            "{}: {verdict}, {} of {} points\n",
            scene.image, grade.points, scene.points
        );
        match &grade.measured {
            Ok(Measured {
                check: Some(Ok(report)),
                ..
            }) => {
                for line in report.findings() {
                    text += &format!("  {line}\n");
                }
            }
            Ok(Measured {
                check: Some(Err(problem)),
                ..
            }) => text += &format!("  raylab's check could not look: {problem}\n"),
            _ => {}
        }
    }
    text += &format!("total: {} of {possible} points\n", grades.total());
    text
}
